#pragma once
// Whether a string is valid UTF-8 (RFC 3629: no overlong forms, no surrogates, at most U+10FFFF).
#include <cstddef>
#include <optional>
#include <string_view>

namespace ecm::io {

// The index of the first byte that does not start or continue a valid sequence; nullopt if valid.
constexpr std::optional<std::size_t> firstInvalidUtf8(std::string_view s) {
  std::size_t i = 0;
  while (i < s.size()) {
    const auto b = static_cast<unsigned char>(s[i]);
    int length = 0;
    unsigned lo = 0x80, hi = 0xBF;  // the allowed range of the second byte
    if (b < 0x80) length = 1;
    else if (b >= 0xC2 && b <= 0xDF) length = 2;
    else if (b == 0xE0) length = 3, lo = 0xA0;
    else if (b >= 0xE1 && b <= 0xEC) length = 3;
    else if (b == 0xED) length = 3, hi = 0x9F;  // no surrogates
    else if (b >= 0xEE && b <= 0xEF) length = 3;
    else if (b == 0xF0) length = 4, lo = 0x90;
    else if (b >= 0xF1 && b <= 0xF3) length = 4;
    else if (b == 0xF4) length = 4, hi = 0x8F;  // at most U+10FFFF
    else return i;
    if (i + static_cast<std::size_t>(length) > s.size()) return i;
    for (int k = 1; k < length; ++k) {
      const auto c = static_cast<unsigned char>(s[i + static_cast<std::size_t>(k)]);
      if (c < (k == 1 ? lo : 0x80u) || c > (k == 1 ? hi : 0xBFu)) return i;
    }
    i += static_cast<std::size_t>(length);
  }
  return std::nullopt;
}

}  // namespace ecm::io
