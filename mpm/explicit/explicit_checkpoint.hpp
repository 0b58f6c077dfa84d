#pragma once
// Checkpoints of a run: DIR/checkpoint.bin holds everything needed to continue the run bitwise
// identically (on any thread count): the solver's step state, every particle array, the
// band states, and the run's output bookkeeping (next output time, history.csv length and hash,
// snapshot times, peak load). Written atomically and durably (checkpoint.bin.tmp, fsync, rename),
// so a crash while writing leaves the previous checkpoint usable.
//
// Format (version 8; numbers in the machine's byte order, checked by a byte-order mark):
//   header, 32 bytes: "ECMMPMCK" | u32 version | u32 0x01020304 | u64 payload bytes |
//                     u64 FNV-1a 64 of the payload
//   payload: u64 scene file hash | i32 threads |
//            step state: f64 time, dt | i64 step | f64 external work, dissipated, damping |
//              i64 sub-stepped updates, snap-back releases, node updates with a raised mass | u64 conditions, each f64 reaction x y,
//              prescribed displacement x y | u64 loads, each f64 applied force x y |
//              u64 d, u32 deferred particles d (USL: the last step's deferred points, index order)
//            platens: u64 q, each f64 displacement 3, force 3, velocity 3 (x, y, rotation) |
//            particles: u64 n | f64 position 2n, origin 2n, velocity 2n, mass n, volume n,
//              strain 3n, stress 3n, strain increment 3n | u8 material n | i32 band n |
//              u64 m (0 or n), f64 integrity m | u64 bands, each f64 crack normal 2, jump 2,
//              onset strain 3, integrity, volume fraction | u64 k (0 or n), i32 second band k |
//              u64 second bands, each as a band |
//            crack paths (mpm/setup/crack_paths.hpp): u64 arms, each u64 points, f64 x y of each,
//              f64 direction x y |
//            scatter order (mpm/explicit/scatter_order.hpp): u64 chunks c, each i32 measured rows lo, hi,
//              planned rows lo, hi
//            run: f64 next output time, peak load, stop_when peak | u64 q, f64 largest |force| 3 of
//              each platen | u64 history.csv bytes, FNV-1a 64, rows |
//              u64 snapshots, f64 their times
// The per-step caches (grid fields, shape-function stencils) are not stored: every step
// rebuilds them before use.
#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "io/csv_writer.hpp"
#include "mpm/explicit/explicit_solver.hpp"
#include "mpm/output/checkpoint_codec.hpp"

namespace ecm::mpm {

// 2: the USL deferred list; 3: the stop_when peak; 4: the second bands; 5: the scatter order;
// 6: the crack paths; 7: the platens; 8: the node updates with a raised mass
inline constexpr std::uint32_t kCheckpointVersion = 8;

// What an explicit run carries besides the solver: the run loop's book and the time of the next
// output row.
struct ExplicitBookkeeping : RunBook {
  double nextOutput = 0.0;  // s
};

// Throws io::OutputError naming the file when it cannot be written (the old one stays).
void writeExplicitCheckpoint(const std::filesystem::path& path, const ExplicitSolver& solver, const ExplicitBookkeeping& run,
                     std::uint64_t sceneHash);

// Restores `solver` (freshly built from the same scene) from the checkpoint and returns the
// run's bookkeeping. Throws CheckpointError, leaving the solver unusable, when the file is
// refused; `sceneHash` must match the one it was written with.
ExplicitBookkeeping readExplicitCheckpoint(const std::filesystem::path& path, ExplicitSolver& solver, std::uint64_t sceneHash);

}  // namespace ecm::mpm
