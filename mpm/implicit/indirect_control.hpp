#pragma once
// Indirect displacement control (docs/implicit.md): the driven conditions' prescribed components
// move by lambda times `reference` (mm per unit load factor), lambda an unknown of each step, and
// the step is set by the growth of a combination of node displacements instead:
// tau = sum_k c_k u_k over node components k = 2 n + d (an opening across a crack, a crack mouth,
// a gauge's reading). The grid is reset every step, so the control is on the step's increments:
// d tau = sum c_k du_k. Here: the control from a scene, and its Newton problem for one piece.
#include <cstdint>
#include <utility>
#include <vector>

#include "mpm/implicit/step_problem.hpp"
#include "mpm/setup/gauge_points.hpp"

namespace ecm::mpm {

struct IndirectControl {
  std::vector<std::size_t> driven;                     // indices of scene conditions
  std::vector<std::size_t> drivenPlatens;              // indices of scene platens (their displacement-driven x, y)
  Vec2 reference = Vec2(0.0, 1.0);                     // mm per unit load factor, on their non-fixed components
  std::vector<std::pair<std::int32_t, double>> terms;  // (node component, coefficient)
};

// The scene's indirect control (solver.control.indirect) in node components: each term on its grid
// node. `reached`: per node, whether the body carries it (reachedNodes). Throws
// std::invalid_argument naming a term on a node no particle reaches (its displacement would stay 0).
IndirectControl indirectControl(const Scene& scene, const std::vector<std::uint8_t>& reached);

// Control on a gauge: its reading's increment over a step is linear in the nodes' increments
// through the shape functions of its particles at the step's start,
// d reading = sum_i N_i(x_to) du_i - sum_i N_i(x_at) du_i: the control's terms, made anew before
// every step as the particles move.
void controlOnGauge(IndirectControl& control, const Gauge& gauge, const GaugePoints& points, const StepSetup& setup,
                    const Particles& particles);

// The last converged step under indirect control: its increments per node component, of the load
// factor and of the opening (0: none yet). The next step's Newton starts from them, scaled.
struct LastIncrement {
  Eigen::VectorXd du;
  double loadFactor = 0.0, opening = 0.0;
};

// Indirect control's Newton problem for a piece of opening dTau: Newton on (du_f, d lambda) with
// the bordered system K_ff d_f + (K u^)_f d_lambda = r_f and c . (d_f + d_lambda u^) = d tau - c . du,
// from the extrapolated start (docs/implicit.md, "The extrapolated start") or from du = 0 (the first
// iteration then is the predictor). The attempt's du holds the iterate without the load factor's
// share until finish().
class IndirectControlStep final : public StepProblem {
 public:
  IndirectControlStep(const StepContext& context, const IndirectControl& control, double dTau, const LastIncrement& last,
                      Attempt& a);

  bool start() override;
  Residual residual(int iteration) override;
  Iterate iterate() const override { return {a_.du, dLambda_}; }
  void move(const Correction& d, const Residual& r, const CycleGuard& cycle) override;
  void backTo(const Iterate* best, const CycleGuard& cycle) override;
  void finish() override;

 private:
  // The trial of the iterate (du plus the load factor's share), which `total_` keeps.
  void evaluate(const CycleGuard* cycle);

  const StepContext& context_;
  const IndirectControl& control_;
  const double dTau_;
  const LastIncrement& last_;
  Attempt& a_;
  Eigen::VectorXd c_;          // the control's coefficients per node component
  Eigen::VectorXd cUnknowns_;  // and over the (reduced) unknowns
  double cPrescribed_ = 0.0;   // d tau per unit load factor through the driven components
  double dLambda_ = 0.0;
  bool extrapolated_ = false;
  Eigen::VectorXd total_;      // the iterate's du with the load factor's share
};

}  // namespace ecm::mpm
