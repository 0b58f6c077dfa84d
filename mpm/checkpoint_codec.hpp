#pragma once
// The pieces of a checkpoint file (mpm/checkpoint.hpp, mpm/implicit_checkpoint.hpp): an encoder
// and a bounds-checked decoder of plain numbers in the machine's byte order, the header that seals
// a payload (signature, format version, byte-order mark, length, FNV-1a 64 checksum), and the
// particle arrays both kinds of checkpoint store.
#include <Eigen/Core>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "mpm/checkpoint.hpp"
#include "mpm/particles.hpp"

namespace ecm::mpm::checkpoint {

class Encoder {
 public:
  template <class T>
    requires std::is_arithmetic_v<T>
  void put(T v) {
    out_.append(reinterpret_cast<const char*>(&v), sizeof v);
  }
  template <int N>
  void put(const Eigen::Matrix<double, N, 1>& v) {
    out_.append(reinterpret_cast<const char*>(v.data()), N * sizeof(double));
  }
  template <class T>
  void array(const std::vector<T>& v) {
    for (const T& x : v) put(x);
  }
  void count(std::size_t n) { put(static_cast<std::uint64_t>(n)); }
  std::string& bytes() { return out_; }

 private:
  std::string out_;
};

// Reads what an Encoder wrote; any overrun is a CheckpointError naming `where`.
class Decoder {
 public:
  Decoder(std::string_view in, std::string where) : in_(in), where_(std::move(where)) {}

  template <class T>
    requires std::is_arithmetic_v<T>
  T get() {
    T v;
    std::memcpy(&v, take(sizeof v), sizeof v);
    return v;
  }
  template <int N>
  void get(Eigen::Matrix<double, N, 1>& v) {
    std::memcpy(v.data(), take(N * sizeof(double)), N * sizeof(double));
  }
  template <class T>
    requires std::is_arithmetic_v<T>
  void get(T& v) {
    v = get<T>();
  }
  template <class T>
  void array(std::vector<T>& v, std::size_t n) {
    need(n, sizeof(T));
    v.resize(n);
    for (T& x : v) get(x);
  }
  // A count of records of `recordBytes` each, checked against what is left (no huge allocations).
  std::size_t count(std::size_t recordBytes) {
    const auto n = get<std::uint64_t>();
    need(n, recordBytes);
    return static_cast<std::size_t>(n);
  }
  bool done() const { return pos_ == in_.size(); }
  [[noreturn]] void fail(const std::string& why) const { throw CheckpointError(where_ + ": " + why); }

 private:
  std::string_view in_;
  std::size_t pos_ = 0;
  std::string where_;

  void need(std::uint64_t n, std::size_t recordBytes) const {
    if (recordBytes > 0 && n > (in_.size() - pos_) / recordBytes) fail("corrupted (a record count runs past the end)");
  }
  const char* take(std::size_t n) {
    if (n > in_.size() - pos_) fail("corrupted (the payload ends early)");
    const char* p = in_.data() + pos_;
    pos_ += n;
    return p;
  }
};

std::string hex(std::uint64_t v);

// Writes header + payload to `path` atomically and durably (io::OutputError when it cannot).
void writeSealed(const std::filesystem::path& path, const char (&magic)[8], std::uint32_t version, const std::string& payload);
// Reads `path` and returns its checked payload in `file` (a view into it), or throws
// CheckpointError naming the file: missing, truncated, corrupted, foreign, of another version.
std::string_view readSealed(const std::filesystem::path& path, const char (&magic)[8], std::uint32_t version,
                            const std::string& what, std::string& file);

// The particle arrays and band states (format in mpm/checkpoint.hpp, "particles").
void putParticles(Encoder& e, const Particles& p);
// Reads them into `p`, whose size, integrity and second-band arrays the scene set; refuses
// (CheckpointError) a count or an index that does not fit it. `materials`: the scene's count.
void getParticles(Decoder& d, Particles& p, std::size_t materials, const std::string& where);

}  // namespace ecm::mpm::checkpoint
