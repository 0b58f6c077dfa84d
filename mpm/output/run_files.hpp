#pragma once
// The files of a run's output folder that both solvers write alike: history.csv (opened new or
// continued after a restart, its first columns the same for both), the final particles
// (particles_final.csv) with their damage map, and the load-displacement plot.
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "io/csv_writer.hpp"
#include "mpm/core/particles.hpp"
#include "mpm/scene/scene.hpp"

namespace ecm::mpm {

// The columns of history.csv both solvers start with: time, step, per condition its
// displacement and reaction, per load its applied force, the energies and the cracked count.
std::vector<std::string> historyColumns(const Scene& scene);
// history.csv of a run in `dir`: continued from `resume` (a restart; a file that does not match
// it is a CheckpointError naming `checkpoint`), or new, after removing a stale `checkpoint` of an
// earlier run in the folder.
std::unique_ptr<io::CsvWriter> openHistory(const std::filesystem::path& dir, const std::vector<std::string>& columns,
                                           const std::filesystem::path& checkpoint, const io::CsvWriter::Resume* resume);
// The final particles (particles_final.csv: x, y, damage, material, opening, normal, stress;
// atomically), the damage map of that file, and the load-displacement PNG of history.csv (its
// first columns: time, step, each condition's displacement and reaction).
void writeParticles(const Particles& particles, const std::filesystem::path& path);
// A CSV written to PATH.tmp and renamed to PATH when `fill` has written its rows: a reader never
// sees half a file (io::OutputError names PATH).
void writeCsvAtomically(const std::filesystem::path& path, const std::vector<std::string>& columns,
                        const std::function<void(io::CsvWriter&)>& fill);
void plotDamage(const Scene& scene, std::size_t particles, const std::filesystem::path& dir);
void plotLoadDisplacement(const Scene& scene, const std::filesystem::path& dir);

}  // namespace ecm::mpm
