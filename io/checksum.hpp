#pragma once
// FNV-1a 64: a small hand-written hash for checksums of checkpoints, history files and scene
// files (not cryptographic; it detects truncation, corruption and accidental changes).
#include <cstddef>
#include <cstdint>
#include <string_view>

namespace ecm::io {

inline constexpr std::uint64_t kFnv1a64Offset = 0xcbf29ce484222325ull;

// Continues the hash `h` over `size` bytes (start with kFnv1a64Offset).
inline std::uint64_t fnv1a64(const void* data, std::size_t size, std::uint64_t h = kFnv1a64Offset) {
  const auto* p = static_cast<const unsigned char*>(data);
  for (std::size_t i = 0; i < size; ++i) {
    h ^= p[i];
    h *= 0x100000001b3ull;
  }
  return h;
}
inline std::uint64_t fnv1a64(std::string_view s, std::uint64_t h = kFnv1a64Offset) { return fnv1a64(s.data(), s.size(), h); }

}  // namespace ecm::io
