// The explicit solver in the run loop (mpm/run_loop.hpp): a step of dt, a history row at every
// output interval, a VTU snapshot at every snapshot_every-th row, checkpoints of the explicit state.
#include "mpm/explicit_run.hpp"

#include <algorithm>

#include "mpm/explicit/explicit_checkpoint.hpp"
#include "mpm/explicit/energy_check.hpp"
#include "mpm/explicit/explicit_solver.hpp"
#include "mpm/output/run_files.hpp"

namespace ecm::mpm {

namespace {

class ExplicitStepper final : public Stepper {
 public:
  ExplicitStepper(const Scene& scene, const RunOptions& options)
      : scene_(scene), solver_(scene, options.threads), nextOutput_(scene.outputInterval) {
    const Energies e = solver_.energies();  // at step 0, also when a checkpoint is read next
    initialEnergy_ = e.kinetic + e.strain;
  }

  const Particles& particles() const override { return solver_.particles(); }
  const Particles& kinematics() const override { return solver_.kinematics(); }
  const CrackPaths& crackPaths() const override { return solver_.state().crackPaths; }
  const std::vector<ConditionState>& conditions() const override { return solver_.conditions(); }
  const std::vector<PlatenState>& platens() const override { return solver_.platens(); }
  std::vector<Vec2> appliedLoads() const override {
    std::vector<Vec2> f;
    for (const LoadState& l : solver_.loads()) f.push_back(l.applied);
    return f;
  }
  long steps() const override { return solver_.step(); }
  double time() const override { return solver_.time(); }
  double progress() const override { return solver_.time(); }
  double progressEnd() const override { return scene_.endTime; }
  // (A half-step tolerance: round-off in the accumulated time adds no step.)
  bool reachedEnd() const override { return solver_.time() >= scene_.endTime - 0.5 * solver_.timeStep(); }
  double progressTolerance() const override { return 0.5 * solver_.timeStep(); }
  std::string progressLabel() const override { return "ecm-mpm " + scene_.name; }

  void advance() override { solver_.advance(); }
  bool rowDue() const override {
    return scene_.outputInterval > 0.0 && solver_.time() >= nextOutput_ - 0.5 * solver_.timeStep();
  }
  void rowWritten() override {
    while (scene_.outputInterval > 0.0 && nextOutput_ <= solver_.time() + 0.5 * solver_.timeStep())
      nextOutput_ += scene_.outputInterval;  // (output_interval 0: the last step only)
  }
  std::vector<std::string> historyColumns() const override { return mpm::historyColumns(scene_); }
  std::vector<double> historyRow() const override {
    std::vector<double> row{solver_.time(), static_cast<double>(solver_.step())};
    for (const auto& c : solver_.conditions())
      row.insert(row.end(), {c.displacement[0], c.displacement[1], c.reaction[0], c.reaction[1]});
    for (const auto& l : solver_.loads()) row.insert(row.end(), {l.applied[0], l.applied[1]});
    const Energies e = solver_.energies();
    row.insert(row.end(), {e.kinetic, e.strain, e.externalWork, e.dissipated, e.damping,
                           static_cast<double>(solver_.particles().bands.size())});
    return row;
  }
  void checkEnergy() const override { checkDampingWork(solver_, initialEnergy_); }
  bool snapshotDue(std::size_t row) const override { return row % static_cast<std::size_t>(scene_.snapshotEvery) == 0; }
  bool failureKeepsConsistentState() const override { return false; }

  RunBook& book() override { return book_; }
  void writeCheckpoint(const std::filesystem::path& path, std::uint64_t sceneHash) override {
    book_.nextOutput = nextOutput_;
    mpm::writeExplicitCheckpoint(path, solver_, book_, sceneHash);
  }
  void readCheckpoint(const std::filesystem::path& path, std::uint64_t sceneHash) override {
    book_ = mpm::readExplicitCheckpoint(path, solver_, sceneHash);
    nextOutput_ = book_.nextOutput;
  }

  nlohmann::json summary(const RunResult& r) const override {
    const Energies e = solver_.energies();
    const Particles& p = solver_.particles();
    nlohmann::json j = {
        {"cracked_particles", p.bands.size()},
        {"bytes_per_particle_uncracked", p.bytesPerParticle()},
        {"bytes_per_particle_cracked", p.bytesPerParticle() + p.bytesPerBand()},
        {"time_step_s", solver_.timeStep()},
        {"end_time_s", solver_.time()},
        {"threads", solver_.threads()},
        {"preset", scene_.preset.empty() ? "none" : scene_.preset},
        {"particles_per_cell", scene_.particlesPerCell},
        {"cfl", scene_.solver.explicitScheme.cfl},
        {"scheme", toString(scene_.solver.explicitScheme.scheme)},
        {"shape_function", toString(scene_.solver.shapeFunction)},
        {"substepped_updates", solver_.substepped()},
        {"mass_scaled_node_updates", solver_.massScaled()},
        {"snap_back_releases", solver_.snapBackReleases()},
        {"particle_updates_per_s",  // of this run's steps (after a restart: those since the checkpoint)
         r.wallTime > 0.0 ? static_cast<double>(r.particles) *
                                static_cast<double>(r.steps - std::max(r.restartedFrom, 0L)) / r.wallTime
                          : 0.0},
        {"energies_Nmm",
         {{"kinetic", e.kinetic}, {"strain", e.strain}, {"external_work", e.externalWork}, {"dissipated", e.dissipated},
          {"damping", e.damping}}},
        {"units", "mm, N, MPa, t, s"}};
    if (!p.secondBand.empty()) {  // second_band: orthogonal (docs/model.md)
      j["two_band_points"] = p.twoBandPoints();
      j["bytes_per_particle_two_bands"] = p.bytesPerParticle() + 2 * p.bytesPerBand();
    }
    // Where the steps' wall time went (of this run's steps: after a restart, those since the checkpoint).
    nlohmann::json phases = nlohmann::json::object();
    for (std::size_t k = 0; k < kStepPhases; ++k)
      if (const double t = solver_.phaseSeconds(static_cast<StepPhase>(k)); t > 0.0) phases[toString(static_cast<StepPhase>(k))] = t;
    j["phase_seconds"] = phases;
    return j;
  }

 private:
  const Scene& scene_;
  ExplicitSolver solver_;  // throws on a scene it cannot seed, before any output
  ExplicitBookkeeping book_;
  double nextOutput_;
  double initialEnergy_ = 0.0;  // kinetic and strain energy at step 0 (N mm): energy_check.hpp
};

}  // namespace

std::unique_ptr<Stepper> explicitStepper(const Scene& scene, const RunOptions& options) {
  return std::make_unique<ExplicitStepper>(scene, options);
}

}  // namespace ecm::mpm
