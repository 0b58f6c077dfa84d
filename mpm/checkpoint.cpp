#include "mpm/checkpoint.hpp"

#include <cstring>
#include <fstream>
#include <string_view>
#include <type_traits>

#include "io/atomic_file.hpp"
#include "io/checksum.hpp"

namespace ecm::mpm {

namespace {

constexpr char kMagic[8] = {'E', 'C', 'M', 'M', 'P', 'M', 'C', 'K'};
constexpr std::uint32_t kByteOrderMark = 0x01020304u;
constexpr std::size_t kHeaderBytes = 32;

// A new field of BandState must be added to the format (and kCheckpointVersion raised).
struct BandStateFields {
  Vec2 crackNormal, jump;
  Voigt onsetStrain;
  double integrity, volumeFraction;
};
static_assert(sizeof(BandStateFields) == sizeof(BandState), "BandState changed: update mpm/checkpoint.cpp");

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

std::string hex(std::uint64_t v) {
  char buf[24];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(v));
  return buf;
}

}  // namespace

void writeCheckpoint(const std::filesystem::path& path, const Solver& solver, const RunBookkeeping& run,
                     std::uint64_t sceneHash) {
  Encoder e;
  e.put(sceneHash);
  e.put(static_cast<std::int32_t>(solver.threads()));

  const Solver::StepState s = solver.stepState();
  e.put(s.time);
  e.put(s.timeStep);
  e.put(static_cast<std::int64_t>(s.step));
  e.put(s.externalWork);
  e.put(s.dissipated);
  e.put(s.damping);
  e.put(static_cast<std::int64_t>(s.substepped));
  e.put(static_cast<std::int64_t>(s.released));
  e.count(s.reactions.size());
  for (std::size_t i = 0; i < s.reactions.size(); ++i) {
    e.put(s.reactions[i]);
    e.put(s.conditionDisplacements[i]);
  }
  e.count(s.appliedLoads.size());
  e.array(s.appliedLoads);
  e.count(s.deferred.size());
  e.array(s.deferred);

  const Particles& p = solver.particles();
  e.count(p.size());
  e.array(p.position);
  e.array(p.origin);
  e.array(p.velocity);
  e.array(p.mass);
  e.array(p.volume);
  e.array(p.strain);
  e.array(p.stress);
  e.array(p.strainIncrement);
  e.array(p.material);
  e.array(p.band);
  e.count(p.integrity.size());
  e.array(p.integrity);
  const auto putBands = [&](const std::vector<BandState>& bands) {
    e.count(bands.size());
    for (const BandState& b : bands) {
      e.put(b.crackNormal);
      e.put(b.jump);
      e.put(b.onsetStrain);
      e.put(b.integrity);
      e.put(b.volumeFraction);
    }
  };
  putBands(p.bands);
  e.count(p.secondBand.size());
  e.array(p.secondBand);
  putBands(p.secondBands);
  const ScatterOrder& order = solver.state().order;  // the scatter's plan and measured rows
  e.count(order.chunks());
  for (std::size_t c = 0; c < order.chunks(); ++c) {
    e.put(static_cast<std::int32_t>(order.measured[c].lo));
    e.put(static_cast<std::int32_t>(order.measured[c].hi));
    e.put(static_cast<std::int32_t>(order.planned[c].lo));
    e.put(static_cast<std::int32_t>(order.planned[c].hi));
  }

  e.put(run.nextOutput);
  e.put(run.peakLoad);
  e.put(run.stopWatchPeak);
  e.put(run.history.bytes);
  e.put(run.history.digest);
  e.put(static_cast<std::uint64_t>(run.history.rows));
  e.count(run.snapshotTimes.size());
  e.array(run.snapshotTimes);

  const std::string& payload = e.bytes();
  Encoder h;
  h.bytes().append(kMagic, sizeof kMagic);
  h.put(kCheckpointVersion);
  h.put(kByteOrderMark);
  h.put(static_cast<std::uint64_t>(payload.size()));
  h.put(io::fnv1a64(payload));
  h.bytes() += payload;
  io::writeFileAtomically(path, h.bytes(), io::Durability::Sync);
}

RunBookkeeping readCheckpoint(const std::filesystem::path& path, Solver& solver, std::uint64_t sceneHash) {
  const std::string where = "checkpoint '" + path.string() + "'";
  auto refuse = [&](const std::string& why) -> void { throw CheckpointError(where + ": " + why); };
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    refuse("no such file (a run leaves one when it is stopped, or as its scene's checkpoint: key asks; a completed "
           "run removes it)");
  const auto size = std::filesystem::file_size(path, ec);
  if (ec) refuse("cannot read it: " + ec.message());
  std::string file(static_cast<std::size_t>(size), '\0');
  std::ifstream in(path, std::ios::binary);
  if (!in.read(file.data(), static_cast<std::streamsize>(file.size()))) refuse("cannot read it");

  // The header: what the file is, then whether all of it is there and intact.
  if (file.size() < sizeof kMagic || std::memcmp(file.data(), kMagic, sizeof kMagic) != 0)
    refuse("not an ecm-mpm checkpoint (no ECMMPMCK signature)");
  if (file.size() < kHeaderBytes) refuse("truncated (" + std::to_string(file.size()) + " bytes, not even a header)");
  Decoder header(std::string_view(file).substr(sizeof kMagic, kHeaderBytes - sizeof kMagic), where);
  const auto version = header.get<std::uint32_t>();
  const auto mark = header.get<std::uint32_t>();
  if (mark != kByteOrderMark) refuse("written on a machine of another byte order");
  if (version != kCheckpointVersion)
    refuse("format version " + std::to_string(version) + "; this ecm-mpm reads version " +
           std::to_string(kCheckpointVersion) + " (resume with the ecm-mpm that wrote it)");
  const auto payloadBytes = header.get<std::uint64_t>();
  const auto checksum = header.get<std::uint64_t>();
  const std::uint64_t expected = kHeaderBytes + payloadBytes;
  if (payloadBytes > file.size() || file.size() != expected)
    refuse((file.size() < expected ? "truncated (" : "corrupted (") + std::to_string(file.size()) +
           " bytes, the header says " + std::to_string(kHeaderBytes) + " + " + std::to_string(payloadBytes) + ")");
  const std::string_view payload = std::string_view(file).substr(kHeaderBytes);
  if (io::fnv1a64(payload) != checksum) refuse("corrupted (checksum mismatch)");

  Decoder d(payload, where);
  const auto hash = d.get<std::uint64_t>();
  if (hash != sceneHash)
    refuse("written for another scene file (scene hash " + hex(hash) + ", this scene's " + hex(sceneHash) +
           "): restart with the scene file the run was started with, unchanged");
  RunBookkeeping run;
  run.threads = d.get<std::int32_t>();

  Solver::StepState s;
  s.time = d.get<double>();
  s.timeStep = d.get<double>();
  s.step = static_cast<long>(d.get<std::int64_t>());
  s.externalWork = d.get<double>();
  s.dissipated = d.get<double>();
  s.damping = d.get<double>();
  s.substepped = static_cast<long>(d.get<std::int64_t>());
  s.released = static_cast<long>(d.get<std::int64_t>());
  const std::size_t conditions = d.count(4 * sizeof(double));
  s.reactions.resize(conditions);
  s.conditionDisplacements.resize(conditions);
  for (std::size_t i = 0; i < conditions; ++i) {
    d.get(s.reactions[i]);
    d.get(s.conditionDisplacements[i]);
  }
  d.array(s.appliedLoads, d.count(2 * sizeof(double)));
  d.array(s.deferred, d.count(sizeof(std::uint32_t)));
  if (conditions != solver.conditions().size() || s.appliedLoads.size() != solver.loads().size())
    refuse("it has " + std::to_string(conditions) + " conditions and " + std::to_string(s.appliedLoads.size()) +
           " loads, the scene " + std::to_string(solver.conditions().size()) + " and " +
           std::to_string(solver.loads().size()));
  // Bitwise: dt follows from the grid and the materials (which the scene hash does not cover
  // when they come from material files).
  if (s.timeStep != solver.timeStep())
    refuse("its time step " + std::to_string(s.timeStep) + " s differs from the scene's " +
           std::to_string(solver.timeStep()) + " s (a material file or the grid changed)");

  Particles& p = solver.editParticles();
  const std::size_t n = d.count(1);
  if (n != p.size())
    refuse("it has " + std::to_string(n) + " particles, the scene " + std::to_string(p.size()));
  d.array(p.position, n);
  d.array(p.origin, n);
  d.array(p.velocity, n);
  d.array(p.mass, n);
  d.array(p.volume, n);
  d.array(p.strain, n);
  d.array(p.stress, n);
  d.array(p.strainIncrement, n);
  d.array(p.material, n);
  d.array(p.band, n);
  const std::size_t integrity = d.count(sizeof(double));
  if (integrity != p.integrity.size())
    refuse("it has " + std::to_string(integrity) + " integrity values, the scene needs " +
           std::to_string(p.integrity.size()));
  d.array(p.integrity, integrity);
  const auto getBands = [&](std::vector<BandState>& states) {
    states.resize(d.count(9 * sizeof(double)));
    for (BandState& b : states) {
      d.get(b.crackNormal);
      d.get(b.jump);
      d.get(b.onsetStrain);
      d.get(b.integrity);
      d.get(b.volumeFraction);
    }
    return states.size();
  };
  const std::size_t bands = getBands(p.bands);
  const std::size_t secondIndex = d.count(sizeof(std::int32_t));
  if (secondIndex != p.secondBand.size())
    refuse("it has " + std::to_string(secondIndex) + " second-band indices, the scene needs " +
           std::to_string(p.secondBand.size()) + " (second_band differs)");
  d.array(p.secondBand, secondIndex);
  const std::size_t secondBands = getBands(p.secondBands);
  std::vector<std::int32_t> rows;
  d.array(rows, 4 * d.count(4 * sizeof(std::int32_t)));
  for (std::size_t i = 0; i < n; ++i) {
    if (p.material[i] >= solver.materials().size())
      refuse("particle " + std::to_string(i) + " has material " + std::to_string(p.material[i]) + " of " +
             std::to_string(solver.materials().size()));
    if (p.band[i] < -1 || (p.band[i] >= 0 && static_cast<std::size_t>(p.band[i]) >= bands))
      refuse("particle " + std::to_string(i) + " refers to band " + std::to_string(p.band[i]) + " of " +
             std::to_string(bands));
    if (!p.secondBand.empty() && (p.secondBand[i] < -1 || (p.secondBand[i] >= 0 && (p.band[i] < 0 ||
                                  static_cast<std::size_t>(p.secondBand[i]) >= secondBands))))
      refuse("particle " + std::to_string(i) + " refers to second band " + std::to_string(p.secondBand[i]) + " of " +
             std::to_string(secondBands));
  }
  ScatterOrder& order = solver.editState().order;
  if (rows.size() != 4 * order.chunks())
    refuse("it has " + std::to_string(rows.size() / 4) + " chunks in its scatter order, the scene " +
           std::to_string(order.chunks()));
  for (std::size_t c = 0; c < order.chunks(); ++c) {
    order.measured[c] = {rows[4 * c], rows[4 * c + 1]};
    order.planned[c] = {rows[4 * c + 2], rows[4 * c + 3]};
  }
  groupChunks(order);

  run.nextOutput = d.get<double>();
  run.peakLoad = d.get<double>();
  run.stopWatchPeak = d.get<double>();
  run.history.bytes = d.get<std::uint64_t>();
  run.history.digest = d.get<std::uint64_t>();
  run.history.rows = static_cast<std::size_t>(d.get<std::uint64_t>());
  d.array(run.snapshotTimes, d.count(sizeof(double)));
  if (!d.done()) refuse("corrupted (bytes left after the payload)");
  try {
    solver.restoreStepState(s);
  } catch (const std::invalid_argument& e) {
    refuse(e.what());
  }
  return run;
}

}  // namespace ecm::mpm
