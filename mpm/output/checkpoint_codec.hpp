#pragma once
// The pieces of a checkpoint file (mpm/explicit/explicit_checkpoint.hpp, mpm/implicit/implicit_checkpoint.hpp): an encoder
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

#include <stdexcept>

#include "io/csv_writer.hpp"
#include "mpm/core/particles.hpp"

namespace ecm::mpm {

// A checkpoint that cannot be used: missing, truncated, corrupted, foreign, of another format
// version, or written for another scene. The message names the file and says why.
struct CheckpointError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// The checkpoint file of a run's output folder (both solvers').
inline std::filesystem::path checkpointPath(const std::filesystem::path& dir) { return dir / "checkpoint.bin"; }

// What the run loop (mpm/run_loop.hpp) carries besides a solver, in both kinds of checkpoint.
struct RunBook {
  double peakLoad = 0.0;              // N
  double stopWatchPeak = 0.0;         // N: the stop_when watch's peak (mpm/scene/stop_when.hpp)
  std::vector<Eigen::Vector3d> platenPeaks;  // per platen: the largest |force| of each degree of freedom so far
  io::CsvWriter::Resume history;      // history.csv up to the checkpoint
  std::vector<double> snapshotTimes;  // the VTU snapshots so far (s; implicit runs: their progress)
  int threads = 0;                    // of the solver that wrote it (read only)
};

}  // namespace ecm::mpm

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

// The payload's head: the scene file's hash and the writer's thread count. getHead refuses a
// checkpoint written for another scene and returns the thread count.
void putHead(Encoder& e, std::uint64_t sceneHash, int threads);
int getHead(Decoder& d, std::uint64_t sceneHash, const std::string& where);
// Per condition its reaction and prescribed displacement (u64 count, then f64 x y of each, in
// turn); getConditions returns the count.
void putConditions(Encoder& e, const std::vector<Vec2>& reactions, const std::vector<Vec2>& displacements);
std::size_t getConditions(Decoder& d, std::vector<Vec2>& reactions, std::vector<Vec2>& displacements);
// The run loop's peaks (peak load, stop_when peak, the platens' peak forces), and its outputs (history.csv's length, hash
// and rows, the snapshot times), as both formats store them.
void putPeaks(Encoder& e, const RunBook& run);
void getPeaks(Decoder& d, RunBook& run);
void putOutputs(Encoder& e, const RunBook& run);
void getOutputs(Decoder& d, RunBook& run);

// Where each platen is, how fast it moves and what it puts on the specimen (PlatenState of
// mpm/setup/step_setup.hpp; its nodes and reference point come from the scene). getPlatens
// refuses a count that is not the scene's.
template <class Platen>
void putPlatens(Encoder& e, const std::vector<Platen>& platens) {
  e.count(platens.size());
  for (const Platen& p : platens) {
    e.put<3>(p.displacement);
    e.put<3>(p.force);
    e.put<3>(p.velocity);
  }
}
template <class Platen>
void getPlatens(Decoder& d, std::vector<Platen>& platens) {
  const std::size_t n = d.count(9 * sizeof(double));
  if (n != platens.size()) d.fail("it has " + std::to_string(n) + " platens, the scene " + std::to_string(platens.size()));
  for (Platen& p : platens) {
    d.get<3>(p.displacement);
    d.get<3>(p.force);
    d.get<3>(p.velocity);
  }
}

// The particle arrays and band states (format in mpm/explicit/explicit_checkpoint.hpp, "particles").
void putParticles(Encoder& e, const Particles& p);
// Reads them into `p`, whose size, integrity and second-band arrays the scene set; refuses
// (CheckpointError) a count or an index that does not fit it. `materials`: the scene's count.
void getParticles(Decoder& d, Particles& p, std::size_t materials, const std::string& where);

}  // namespace ecm::mpm::checkpoint
