#pragma once
// Checkpoints of implicit_static runs (docs/implicit.md): DIR/checkpoint.bin, like an explicit
// run's (mpm/explicit/explicit_checkpoint.hpp) but with the implicit solver's state, so a restarted run continues
// bitwise as the uninterrupted one, on any thread count. Written atomically and durably.
//
// Format (version 7; numbers in the machine's byte order):
//   header, 32 bytes: "ECMIMPCK" | u32 version | u32 0x01020304 | u64 payload bytes | u64 FNV-1a 64
//   payload: u64 scene file hash | i32 threads |
//            solver: f64 time, load factor, next piece (pseudo-time), next opening (mm) | i64 steps | f64 external work, internal
//              work, dissipated, the dashpots' work | i64 snap-back releases | u64 conditions, each f64 reaction x y,
//              prescribed displacement x y |
//            geometry: u64 g, i32 stencil first node g | u64 c, u8 prescribed c |
//              factorised tangent: i64 rows (0: none), u64 nnz, i32 outer rows+1, i32 inner nnz, f64 nnz,
//                u8 of reduced unknowns, u64 q, u8 3 of each platen (its prescribed DOFs), u64 t, each
//                node tie i32 node, sources, source 4, f64 coefficient 4 (mpm/implicit/node_ties.hpp) |
//            indirect control: u64 i, f64 the last step's increments i | f64 last load factor increment,
//              last opening |
//            platens, particles and crack paths (as mpm/explicit/explicit_checkpoint.hpp) |
//            run: f64 progress, next snapshot, peak load, stop_when peak, u64 q, f64 3 of each platen, linear-solve seconds | i64 iterations,
//              halvings, releases, factorisations, most iterations in a step, relaxed steps, Krylov iterations, stabilised steps |
//              u64 history.csv bytes, FNV-1a 64, rows | u64 snapshots, f64 their times
#include <cstdint>
#include <filesystem>
#include <vector>

#include "io/csv_writer.hpp"
#include "mpm/output/checkpoint_codec.hpp"
#include "mpm/implicit/implicit_solver.hpp"

namespace ecm::mpm {

// 2: the adaptive opening step, the stop_when peak; 3: the last step's increments (indirect control);
// 4: the Krylov iterations on the kept factorisation; 5: the crack paths; 6: the platens, and the
// reduction a factorised tangent of reduced unknowns was made for; 7: the stabilised steps and their
// dashpots' work
inline constexpr std::uint32_t kImplicitCheckpointVersion = 7;

// What an implicit run carries besides the solver: the run loop's book, the progress and the
// solver's counters.
struct ImplicitBookkeeping : RunBook {
  double progress = 0.0;       // pseudo-time (s), then under indirect control `from` + the opening tau (mm) reached
  double nextSnapshot = 0.0;   // of the VTU series, in the same unit
  double linearSolveSeconds = 0.0;
  long iterations = 0, halvings = 0, released = 0, factorizations = 0, mostIterations = 0, relaxed = 0;
  long krylovIterations = 0;  // GMRES vectors on the kept factorisation
  long stabilized = 0;        // load steps solved by proximal steps (docs/implicit.md, "Stabilised steps")
};

// Throws io::OutputError naming the file when it cannot be written (the old one stays).
void writeImplicitCheckpoint(const std::filesystem::path& path, const ImplicitSolver& solver, const ImplicitBookkeeping& run,
                             std::uint64_t sceneHash);
// Restores `solver` (freshly built from the same scene) and returns the bookkeeping; throws
// CheckpointError naming the file and the reason when it is refused.
ImplicitBookkeeping readImplicitCheckpoint(const std::filesystem::path& path, ImplicitSolver& solver, std::uint64_t sceneHash);

}  // namespace ecm::mpm
