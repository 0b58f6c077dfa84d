#pragma once
// Loud failures of a run: what kind, the step, the particle, where it was and why. The kind is
// data from where a failure is detected to RunResult, summary.json ("failure.kind"), ecm-mpm's
// exit status and the Python module's exception class; no caller reads the message to find it
// (docs/tools.md, "When a run fails").
#include <array>
#include <cstddef>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>

#include "material/update_result.hpp"

namespace ecm::mpm {

enum class FailureKind {
  LeftGrid,            // a particle (or its shape-function support) left the background grid
  NotFinite,           // NaN or infinity in a particle's velocity, position or stress
  MaterialFailure,     // a material update did not converge even after sub-stepping
  SnapBack,            // a material snap-back under snap_back: stop (the band has no stable branch)
  NewtonNotConverged,  // implicit: Newton did not converge on the smallest piece of a step
  SingularTangent,     // implicit: the tangent was singular on the smallest piece
  OnsetOvershoot,      // implicit: even the smallest piece carried a point too far past its onset
  ControlBlind,        // implicit, indirect control: the opening does not change with the load factor
  DampingWork,         // the damping's work (explicit) or the stabilised steps' dashpots' (implicit) passed the energy put in
  WorkImbalance,       // implicit: the external and internal works parted (steps not in equilibrium)
  Output,              // a file could not be written once the run had begun (full disk?)
};

// One row per kind: its name in summary.json and the Python module, ecm-mpm's exit status
// (io/cli_exit.hpp: 10 and up, one per kind) and what it means.
struct FailureKindInfo {
  FailureKind kind;
  std::string_view name;
  int exitStatus;
  std::string_view meaning;
};
extern const std::array<FailureKindInfo, 11> kFailureKinds;
const FailureKindInfo& infoOf(FailureKind k);
inline std::string_view toString(FailureKind k) { return infoOf(k).name; }
inline int exitStatusOf(FailureKind k) { return infoOf(k).exitStatus; }

// How a run failed, as RunResult and summary.json carry it.
struct RunFailure {
  FailureKind kind = FailureKind::Output;
  std::string message;                  // what ecm-mpm prints: the step, the particle, the numbers
  long step = 0;                        // the step during which it happened (1-based; 0: before the first)
  std::optional<std::size_t> particle;  // the particle it happened at, if one (index in the seeding order)
  std::optional<Vec2> position;         // mm, of that particle
  UpdateStatus materialStatus = UpdateStatus::Converged;  // MaterialFailure, SnapBack: how the update failed
  double residual = 0.0;  // MaterialFailure: the update's (MPa); implicit kinds: Newton's relative residual; WorkImbalance: the gap's share of the work
  // Implicit, displacement control: Newton failed on the smallest piece of a cracked structure,
  // most likely past a limit point, which indirect control traces (docs/implicit.md).
  bool likelyLimitPoint = false;
  std::filesystem::path file;  // Output: the file that could not be written
};

// A file that could not be written once the run had begun.
inline RunFailure outputFailureOf(std::string message, long step, std::filesystem::path file) {
  RunFailure f;
  f.message = std::move(message);
  f.step = step;
  f.file = std::move(file);
  return f;
}

struct SimulationError : std::runtime_error {
  SimulationError(FailureKind k, long stepIndex, std::optional<std::size_t> particleId, const Vec2& x, const std::string& what,
                  UpdateStatus s = UpdateStatus::Converged, double r = 0.0)
      : std::runtime_error(what), kind(k), step(stepIndex), particle(particleId), position(x), status(s), residual(r) {}
  FailureKind kind;
  long step;                            // the step during which it happened (1-based)
  std::optional<std::size_t> particle;  // particle id (index in the seeding order), if the failure has one
  Vec2 position;                        // mm (of the particle)
  UpdateStatus status;                  // MaterialFailure, SnapBack
  double residual;                      // see RunFailure::residual
  bool likelyLimitPoint = false;        // see RunFailure::likelyLimitPoint

  RunFailure failure() const {
    RunFailure f;
    f.kind = kind;
    f.message = what();
    f.step = step;
    f.particle = particle;
    if (particle) f.position = position;
    f.materialStatus = status;
    f.residual = residual;
    f.likelyLimitPoint = likelyLimitPoint;
    return f;
  }
};

}  // namespace ecm::mpm
