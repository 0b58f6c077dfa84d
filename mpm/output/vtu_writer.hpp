#pragma once
// Particle snapshots for ParaView: one .vtu per output step (points as vertex cells, arrays raw
// appended: Float32 fields, Float64 positions) and a .pvd index listing them with their times.
// Fields: displacement, velocity, stress, strain, damage, crack normal, jump and normal opening,
// material id, cracked flag.
#include <filesystem>
#include <string>
#include <vector>

#include "mpm/core/particles.hpp"

namespace ecm::mpm {

// Writes the particles to `path` (atomically: a reader never sees half a file).
// `scratch`: a buffer kept between snapshots (no fresh pages to fault in for every one).
void writeVtu(const Particles& particles, double time, const std::filesystem::path& path, std::string* scratch = nullptr);

// The .pvd collection of a run; add() writes a snapshot and rewrites the index.
class VtuSeries {
 public:
  // Snapshots go to DIR/particles_NNNNN.vtu, the index to DIR/particles.pvd.
  explicit VtuSeries(std::filesystem::path dir, std::string stem = "particles");
  void add(const Particles& particles, double time);  // time: s (pseudo-time for implicit runs)
  std::size_t size() const { return entries_.size(); }
  std::filesystem::path indexPath() const { return dir_ / (stem_ + ".pvd"); }
  std::vector<double> times() const;  // of the snapshots so far (s)
  // Continues the series of an earlier run whose snapshots at `times` are on disk (a restart):
  // the snapshots it wrote after them are removed and the index is rewritten.
  void resume(const std::vector<double>& times);

 private:
  std::string fileName(std::size_t index) const;
  void writeIndex() const;
  std::filesystem::path dir_;
  std::string stem_;
  std::vector<std::pair<double, std::string>> entries_;  // time (s), file name
  std::string scratch_;  // the appended arrays of the last snapshot, reused
};

}  // namespace ecm::mpm
