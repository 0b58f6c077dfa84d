// The implicit_static solver in the run loop (mpm/implicit_run.hpp): one adaptive load step at a
// time (ImplicitSolver::advance) to the end of the pseudo-time, or of the opening under indirect
// control; a history row per load step; VTU snapshots at every snapshot_every-th multiple of
// output_interval (pseudo-time, or mm of opening) and at the start and end.
#include "mpm/implicit_run.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

#include "mpm/implicit/implicit_checkpoint.hpp"
#include "mpm/implicit/implicit_solver.hpp"
#include "mpm/output/run_files.hpp"
#include "mpm/setup/gauge_points.hpp"

namespace ecm::mpm {

namespace {

class ImplicitStepper final : public Stepper {
 public:
  ImplicitStepper(const Scene& scene, const RunOptions& options)
      : scene_(scene), settings_(*scene.solver.implicit), solver_(scene, options.threads) {
    if (settings_.indirect) control_ = indirectControl(scene, reachedNodes(solver_.setup(), solver_.particles()));
    gaugePoints_ = locateGauges(scene, solver_.particles());
    // The progress: load steps of pseudo-time to `from_` (the end time without indirect
    // control), then the indirect control's steps of opening: `from_` plus the opening (mm).
    from_ = settings_.indirect ? settings_.indirect->from : scene.endTime;
    total_ = settings_.indirect ? from_ + settings_.indirect->until : scene.endTime;
  }

  const Particles& particles() const override { return solver_.particles(); }
  const CrackPaths& crackPaths() const override { return solver_.crackPaths(); }
  const std::vector<ConditionState>& conditions() const override { return solver_.conditions(); }
  const std::vector<PlatenState>& platens() const override { return solver_.platens(); }
  std::vector<Vec2> appliedLoads() const override {
    std::vector<Vec2> f;
    for (const Load& l : scene_.loads) f.push_back(l.force * l.history(solver_.time()));
    return f;
  }
  long steps() const override { return solver_.steps(); }
  double time() const override { return solver_.time(); }
  double progress() const override { return book_.progress; }
  double progressEnd() const override { return total_; }
  bool reachedEnd() const override { return book_.progress >= total_ * (1.0 - 1e-12); }
  double progressTolerance() const override { return 1e-12 * total_; }
  std::string progressLabel() const override { return "ecm-mpm " + scene_.name + " (implicit)"; }

  void advance() override {
    const bool controlled = settings_.indirect && book_.progress >= from_ * (1.0 - 1e-12);
    if (controlled && !settings_.indirect->gauge.empty()) gaugeControl();
    last_ = controlled ? solver_.advance(control_, settings_.indirect->step, total_ - book_.progress)
                       : solver_.advance(settings_.loadStep, from_ - book_.progress);
    book_.progress += last_.size;
    if (!controlled && std::abs(book_.progress - from_) <= 1e-12 * from_) book_.progress = from_;
    book_.iterations += last_.totalIterations, book_.halvings += last_.cuts, book_.released += last_.released;
    book_.factorizations += last_.factorizations;
    book_.krylovIterations += last_.krylovIterations;
    book_.relaxed += last_.relaxed;
    book_.stabilized += last_.proximalSteps > 0 ? 1 : 0;
    book_.mostIterations = std::max(book_.mostIterations, static_cast<long>(last_.totalIterations));
    book_.linearSolveSeconds += last_.linearSolveSeconds;
  }
  bool rowDue() const override { return true; }  // a row per load step
  void rowWritten() override {}
  std::vector<std::string> historyColumns() const override {
    std::vector<std::string> columns = mpm::historyColumns(scene_);
    for (const char* c : {"load_factor", "newton_iterations", "halvings", "snapback_releases", "load_step", "onset_overshoot",
                          "internal_work_Nmm", "work_dissipated_Nmm", "relaxed", "proximal_steps"})
      columns.emplace_back(c);
    return columns;
  }
  // The explicit columns (kinetic energy and damping 0), then the implicit ones of the last step.
  std::vector<double> historyRow() const override {
    const ImplicitStepReport& r = last_;
    std::vector<double> v{solver_.time(), static_cast<double>(solver_.steps())};
    for (const ConditionState& c : solver_.conditions()) v.insert(v.end(), {c.displacement[0], c.displacement[1], c.reaction[0], c.reaction[1]});
    for (const Vec2& f : appliedLoads()) v.insert(v.end(), {f[0], f[1]});
    const Energies e = solver_.energies();
    v.insert(v.end(), {0.0, e.strain, e.externalWork, e.dissipated, e.damping, static_cast<double>(cracked()), solver_.loadFactor(),
                       static_cast<double>(r.totalIterations), static_cast<double>(r.cuts), static_cast<double>(r.released),
                       r.size, r.onsetOvershoot, solver_.internalWork(), solver_.internalWork() - e.strain,
                       static_cast<double>(r.relaxed), static_cast<double>(r.proximalSteps)});
    return v;
  }
  // At the first row, and where the progress passes the next multiple of the spacing.
  bool snapshotDue(std::size_t row) const override {
    return row == 0 || (spacing() > 0.0 && book_.progress >= book_.nextSnapshot * (1.0 - 1e-12));
  }
  void snapshotTaken() override {
    while (spacing() > 0.0 && book_.nextSnapshot <= book_.progress * (1.0 + 1e-12)) book_.nextSnapshot += spacing();
  }
  bool failureKeepsConsistentState() const override { return true; }

  RunBook& book() override { return book_; }
  void writeCheckpoint(const std::filesystem::path& path, std::uint64_t sceneHash) override {
    writeImplicitCheckpoint(path, solver_, book_, sceneHash);
  }
  void readCheckpoint(const std::filesystem::path& path, std::uint64_t sceneHash) override {
    book_ = readImplicitCheckpoint(path, solver_, sceneHash);
  }

  nlohmann::json summary([[maybe_unused]] const RunResult& r) const override {
    nlohmann::json j;
    j["units"] = "mm, N, MPa, t, s (time: pseudo-time)";
    j["scheme"] = "implicit_static";
    j["control"] = settings_.indirect ? "indirect" : "displacement";
    j["load_factor"] = solver_.loadFactor();
    j["newton_iterations"] = book_.iterations;
    j["newton_iterations_per_step"] =
        solver_.steps() > 0 ? static_cast<double>(book_.iterations) / static_cast<double>(solver_.steps()) : 0.0;
    j["most_newton_iterations_in_a_step"] = book_.mostIterations;
    j["halvings"] = book_.halvings;
    j["factorizations"] = book_.factorizations;
    j["krylov_iterations"] = book_.krylovIterations;
    j["linear_solve_s"] = book_.linearSolveSeconds;
    j["linear_solver"] = toString(settings_.linearSolver);
    if (const std::optional<long> copies = solver_.linearSolver().factorCopies())
      j["factor_copies"] = *copies;  // by runs, of this process's factorisations (UMFPACK)
    if (const AmgStatistics* amg = solver_.linearSolver().amgStatistics())
      j["amg"] = {{"hierarchies", amg->setups},         {"solves", amg->solves},
                  {"gmres_iterations", amg->iterations}, {"failed_solves", amg->failedSolves},
                  {"setup_s", amg->setupSeconds},        {"solve_s", amg->solveSeconds}};
    j["snap_back_releases"] = book_.released;
    j["relaxed_steps"] = book_.relaxed;  // kept with a residual between tolerance and accept_tolerance
    // Load steps solved by proximal steps, and their dashpots' work (docs/implicit.md, "Stabilised steps")
    j["stabilized_steps"] = book_.stabilized;
    j["cracked_particles"] = cracked();
    const Energies e = solver_.energies();
    // Two dissipations (docs/implicit.md, "Energies"): the model's f int Y dD, and the internal
    // work minus the strain energy, which the external work balances step by step.
    j["energies_Nmm"] = {{"strain", e.strain},
                         {"external_work", e.externalWork},
                         {"internal_work", solver_.internalWork()},
                         {"dissipated", e.dissipated},
                         {"work_dissipated", solver_.internalWork() - e.strain},
                         {"dashpots", e.damping}};
    j["energy_balance"] = std::abs(e.externalWork - solver_.internalWork()) / std::max(std::abs(e.externalWork), 1e-300);
    j["threads"] = solver_.setup().threads;
    return j;
  }

 private:
  double spacing() const { return scene_.outputInterval * scene_.snapshotEvery; }
  // Indirect control on a gauge (controlOnGauge): its terms made anew before every step.
  void gaugeControl() {
    const auto g = static_cast<std::size_t>(std::find_if(scene_.gauges.begin(), scene_.gauges.end(), [&](const Gauge& x) {
                                              return x.name == settings_.indirect->gauge;
                                            }) - scene_.gauges.begin());
    controlOnGauge(control_, scene_.gauges[g], gaugePoints_[g], solver_.setup(), solver_.particles());
  }
  long cracked() const {
    long n = 0;
    for (const auto b : solver_.particles().band) n += b >= 0 ? 1 : 0;
    return n;
  }

  const Scene& scene_;
  const ImplicitSettings& settings_;
  ImplicitSolver solver_;  // throws on a scene it cannot seed, before any output
  IndirectControl control_;
  std::vector<GaugePoints> gaugePoints_;  // of the scene's gauges (for control on a gauge)
  double from_ = 0.0, total_ = 0.0;
  ImplicitBookkeeping book_;
  ImplicitStepReport last_;  // of the last load step (zero before the first)
};

}  // namespace

std::unique_ptr<Stepper> implicitStepper(const Scene& scene, const RunOptions& options) {
  return std::make_unique<ImplicitStepper>(scene, options);
}

}  // namespace ecm::mpm
