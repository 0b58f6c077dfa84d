// The pieces of a checkpoint file (mpm/output/checkpoint_codec.hpp).
#include "mpm/output/checkpoint_codec.hpp"

#include <cstdio>
#include <fstream>

#include "io/atomic_file.hpp"
#include "io/checksum.hpp"

namespace ecm::mpm::checkpoint {

namespace {

constexpr std::uint32_t kByteOrderMark = 0x01020304u;
constexpr std::size_t kHeaderBytes = 32;

// A new field of BandState must be added to the format (and the format versions raised).
struct BandStateFields {
  Vec2 crackNormal, jump;
  Voigt onsetStrain;
  double integrity, volumeFraction;
};
static_assert(sizeof(BandStateFields) == sizeof(BandState), "BandState changed: update mpm/output/checkpoint_codec.cpp");

}  // namespace

std::string hex(std::uint64_t v) {
  char buf[24];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(v));
  return buf;
}

void writeSealed(const std::filesystem::path& path, const char (&magic)[8], std::uint32_t version, const std::string& payload) {
  Encoder h;
  h.bytes().append(magic, sizeof magic);
  h.put(version);
  h.put(kByteOrderMark);
  h.put(static_cast<std::uint64_t>(payload.size()));
  h.put(io::fnv1a64(payload));
  h.bytes() += payload;
  io::writeFileAtomically(path, h.bytes(), io::Durability::Sync);
}

std::string_view readSealed(const std::filesystem::path& path, const char (&magic)[8], std::uint32_t version,
                            const std::string& what, std::string& file) {
  const std::string where = "checkpoint '" + path.string() + "'";
  auto refuse = [&](const std::string& why) -> void { throw CheckpointError(where + ": " + why); };
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    refuse("no such file (a run leaves one when it is stopped, or as its scene's checkpoint: key asks; a completed "
           "run removes it)");
  const auto size = std::filesystem::file_size(path, ec);
  if (ec) refuse("cannot read it: " + ec.message());
  file.assign(static_cast<std::size_t>(size), '\0');
  std::ifstream in(path, std::ios::binary);
  if (!in.read(file.data(), static_cast<std::streamsize>(file.size()))) refuse("cannot read it");

  // The header: what the file is, then whether all of it is there and intact.
  if (file.size() < sizeof magic || std::memcmp(file.data(), magic, sizeof magic) != 0)
    refuse("not " + what + " (no " + std::string(magic, sizeof magic) + " signature)");
  if (file.size() < kHeaderBytes) refuse("truncated (" + std::to_string(file.size()) + " bytes, not even a header)");
  Decoder header(std::string_view(file).substr(sizeof magic, kHeaderBytes - sizeof magic), where);
  const auto fileVersion = header.get<std::uint32_t>();
  const auto mark = header.get<std::uint32_t>();
  if (mark != kByteOrderMark) refuse("written on a machine of another byte order");
  if (fileVersion != version)
    refuse("format version " + std::to_string(fileVersion) + "; this ecm-mpm reads version " + std::to_string(version) +
           " (resume with the ecm-mpm that wrote it)");
  const auto payloadBytes = header.get<std::uint64_t>();
  const auto checksum = header.get<std::uint64_t>();
  const std::uint64_t expected = kHeaderBytes + payloadBytes;
  if (payloadBytes > file.size() || file.size() != expected)
    refuse((file.size() < expected ? "truncated (" : "corrupted (") + std::to_string(file.size()) +
           " bytes, the header says " + std::to_string(kHeaderBytes) + " + " + std::to_string(payloadBytes) + ")");
  const std::string_view payload = std::string_view(file).substr(kHeaderBytes);
  if (io::fnv1a64(payload) != checksum) refuse("corrupted (checksum mismatch)");
  return payload;
}

void putParticles(Encoder& e, const Particles& p) {
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
}

void getParticles(Decoder& d, Particles& p, std::size_t materials, const std::string& where) {
  auto refuse = [&](const std::string& why) -> void { throw CheckpointError(where + ": " + why); };
  const std::size_t n = d.count(1);
  if (n != p.size()) refuse("it has " + std::to_string(n) + " particles, the scene " + std::to_string(p.size()));
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
  for (std::size_t i = 0; i < n; ++i) {
    if (p.material[i] >= materials)
      refuse("particle " + std::to_string(i) + " has material " + std::to_string(p.material[i]) + " of " +
             std::to_string(materials));
    if (p.band[i] < -1 || (p.band[i] >= 0 && static_cast<std::size_t>(p.band[i]) >= bands))
      refuse("particle " + std::to_string(i) + " refers to band " + std::to_string(p.band[i]) + " of " +
             std::to_string(bands));
    if (!p.secondBand.empty() && (p.secondBand[i] < -1 || (p.secondBand[i] >= 0 && (p.band[i] < 0 ||
                                  static_cast<std::size_t>(p.secondBand[i]) >= secondBands))))
      refuse("particle " + std::to_string(i) + " refers to second band " + std::to_string(p.secondBand[i]) + " of " +
             std::to_string(secondBands));
  }
}

void putHead(Encoder& e, std::uint64_t sceneHash, int threads) {
  e.put(sceneHash);
  e.put(static_cast<std::int32_t>(threads));
}

int getHead(Decoder& d, std::uint64_t sceneHash, const std::string& where) {
  const auto hash = d.get<std::uint64_t>();
  if (hash != sceneHash)
    throw CheckpointError(where + ": written for another scene file (scene hash " + hex(hash) + ", this scene's " + hex(sceneHash) +
                          "): restart with the scene file the run was started with, unchanged");
  return d.get<std::int32_t>();
}

void putConditions(Encoder& e, const std::vector<Vec2>& reactions, const std::vector<Vec2>& displacements) {
  e.count(reactions.size());
  for (std::size_t i = 0; i < reactions.size(); ++i) {
    e.put(reactions[i]);
    e.put(displacements[i]);
  }
}

std::size_t getConditions(Decoder& d, std::vector<Vec2>& reactions, std::vector<Vec2>& displacements) {
  const std::size_t conditions = d.count(4 * sizeof(double));
  reactions.resize(conditions);
  displacements.resize(conditions);
  for (std::size_t i = 0; i < conditions; ++i) {
    d.get(reactions[i]);
    d.get(displacements[i]);
  }
  return conditions;
}

void putPeaks(Encoder& e, const RunBook& run) {
  e.put(run.peakLoad);
  e.put(run.stopWatchPeak);
  e.count(run.platenPeaks.size());
  for (const Eigen::Vector3d& p : run.platenPeaks) e.put<3>(p);
}

void getPeaks(Decoder& d, RunBook& run) {
  run.peakLoad = d.get<double>();
  run.stopWatchPeak = d.get<double>();
  run.platenPeaks.resize(d.count(3 * sizeof(double)));
  for (Eigen::Vector3d& p : run.platenPeaks) d.get<3>(p);
}


void putOutputs(Encoder& e, const RunBook& run) {
  e.put(run.history.bytes);
  e.put(run.history.digest);
  e.put(static_cast<std::uint64_t>(run.history.rows));
  e.count(run.snapshotTimes.size());
  e.array(run.snapshotTimes);
}

void getOutputs(Decoder& d, RunBook& run) {
  run.history.bytes = d.get<std::uint64_t>();
  run.history.digest = d.get<std::uint64_t>();
  run.history.rows = static_cast<std::size_t>(d.get<std::uint64_t>());
  d.array(run.snapshotTimes, d.count(sizeof(double)));
}

}  // namespace ecm::mpm::checkpoint
