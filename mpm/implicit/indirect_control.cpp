// Indirect displacement control (mpm/implicit/indirect_control.hpp).
#include "mpm/implicit/indirect_control.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

#include "mpm/implicit/node_ties.hpp"

namespace ecm::mpm {

IndirectControl indirectControl(const Scene& scene, const std::vector<std::uint8_t>& reached) {
  const ImplicitSettings::Indirect& in = *scene.solver.implicit->indirect;
  IndirectControl c;
  for (const std::string& name : in.driven) {  // conditions and platens (validated: each is one of them)
    if (const auto i = findCondition(scene.conditions, name)) {
      c.driven.push_back(*i);
      continue;
    }
    for (std::size_t p = 0; p < scene.platens.size(); ++p)
      if (scene.platens[p].name == name) c.drivenPlatens.push_back(p);
  }
  c.reference = in.reference;
  const Grid& g = scene.grid;
  for (std::size_t k = 0; k < in.terms.size(); ++k) {
    const ControlTerm& t = in.terms[k];
    const Vec2 local = (t.at - g.origin).cwiseQuotient(g.cellSize);
    const int i = static_cast<int>(std::lround(local[0])), j = static_cast<int>(std::lround(local[1]));
    if (!reached[static_cast<std::size_t>(g.node(i, j))]) {
      std::ostringstream msg;
      msg << "solver.control.indirect.opening[" << k << "]: the node (" << t.at[0] << ", " << t.at[1]
          << ") mm is reached by no particle (no material around it): its displacement would stay 0; name nodes of the body";
      throw std::invalid_argument(msg.str());
    }
    c.terms.push_back({2 * g.node(i, j) + t.component, t.coefficient});
  }
  return c;
}

void controlOnGauge(IndirectControl& control, const Gauge& gauge, const GaugePoints& points, const StepSetup& setup,
                    const Particles& particles) {
  const Scene& scene = setup.scene;
  const Grid& grid = scene.grid;
  const int support = supportSize(scene.solver.shapeFunction);
  control.terms.clear();
  const auto add = [&](std::size_t particle, double sign) {
    Stencil s;
    if (!computeStencil(scene.solver.shapeFunction, grid, setup.halfWidth, particles.position[particle], s)) return;
    for (int j = 0; j < support; ++j)
      for (int k = 0; k < support; ++k)
        if (const double w = s.wx[k] * s.wy[j]; w != 0.0) control.terms.push_back({2 * (s.base + j * grid.nodesX() + k) + gauge.component, sign * w});
  };
  if (gauge.to) add(points.to, 1.0);
  add(points.at, gauge.to ? -1.0 : 1.0);
}

IndirectControlStep::IndirectControlStep(const StepContext& context, const IndirectControl& control, double dTau,
                                         const LastIncrement& last, Attempt& a)
    : context_(context), control_(control), dTau_(dTau), last_(last), a_(a) {}

void IndirectControlStep::evaluate(const CycleGuard* cycle) {
  total_ = a_.du + dLambda_ * a_.direction;
  evaluateTrial(context_.setup, context_.particles, context_.geometry, total_, false, a_.snapBack, a_.trial, &a_.direction,
                cycle ? cycle->secantFlags() : nullptr, a_.keptStarts());
}

// The start: the last step's increments scaled to this step's opening (docs/implicit.md, "The
// extrapolated start"): it meets the control exactly, and Newton begins near the solution of a
// smooth path. The internal forces at du = 0 (for the work) are then evaluated apart.
bool IndirectControlStep::start() {
  Attempt& a = a_;
  const StepContext& c = context_;
  const auto components = a.du.size();
  const DofMap& dofs = c.geometry.dofs;
  c_ = Eigen::VectorXd::Zero(components);
  for (const auto& [k, coefficient] : control_.terms) c_[k] += coefficient;
  cUnknowns_ = onUnknowns(dofs, a.unknownReduction(), [&](std::int32_t k) { return c_[k]; });
  cPrescribed_ = c_.dot(a.direction);
  if (c.settings.extrapolate && last_.opening != 0.0 && last_.du.size() == components) {
    Trial zero;
    evaluateTrial(c.setup, c.particles, c.geometry, Eigen::VectorXd::Zero(components), false, a.snapBack, zero);
    if (zero.failed != SIZE_MAX) return a.failInMaterial(0, zero, c.setup, c.particles);
    a.startForce = zero.internalForce;
    const double scale = dTau_ / last_.opening;
    for (int u = 0; u < dofs.unknowns(); ++u) {  // (a platen's node components: without the load factor's share)
      const auto k = dofs.component[static_cast<std::size_t>(u)];
      const double d = a.direction[k];
      a.du[k] = scale * (d == 0.0 ? last_.du[k] : last_.du[k] - last_.loadFactor * d);
    }
    applyTies(a.ties, a.du);  // the last step may have tied other nodes
    dLambda_ = scale * last_.loadFactor;
    extrapolated_ = true;
  }
  evaluate(nullptr);
  if (!extrapolated_) a.startForce = a.trial.internalForce;  // du = 0
  return true;
}

Residual IndirectControlStep::residual(int iteration) {
  const Attempt& a = a_;
  const Trial& t = a.trial;
  const DofMap& dofs = context_.geometry.dofs;
  const UnknownReduction* reduction = a.unknownReduction();
  Residual res;
  res.r = onUnknowns(dofs, reduction, [&](std::int32_t k) { return a.external[k] - t.internalForce[k]; });
  ControlRow row;
  row.ku = onUnknowns(dofs, reduction, [&](std::int32_t k) { return t.tangentTimesDirection[k]; });
  row.c = &cUnknowns_;
  row.cPrescribed = cPrescribed_;
  row.g = dTau_ - c_.dot(total_);
  res.relative = res.r.norm() / std::max({a.external.norm(), t.internalForce.norm(), 1e-300});
  res.meetsControl = std::abs(row.g) <= 1e-10 * std::abs(dTau_);
  res.mayConverge = iteration > 0 || extrapolated_;  // from rest, the first iterate is the predictor's base
  res.border = std::move(row);
  return res;
}

void IndirectControlStep::move(const Correction& d, const Residual&, const CycleGuard& cycle) {
  const DofMap& dofs = context_.geometry.dofs;
  if (const UnknownReduction* reduction = a_.unknownReduction()) {
    const Eigen::VectorXd onNodes = toUnknowns(reduction, d.step);
    for (int u = 0; u < dofs.unknowns(); ++u) a_.du[dofs.component[static_cast<std::size_t>(u)]] += onNodes[u];
  } else {
    for (int u = 0; u < dofs.unknowns(); ++u) a_.du[dofs.component[static_cast<std::size_t>(u)]] += d.step[u];
  }
  dLambda_ += d.loadFactor;
  evaluate(&cycle);
}

void IndirectControlStep::backTo(const Iterate* best, const CycleGuard& cycle) {
  if (!best) return;
  dLambda_ = best->loadFactor;
  a_.du = best->du;
  evaluate(&cycle);
}

void IndirectControlStep::finish() {
  a_.du = total_;
  a_.dLambda = dLambda_;
  a_.dTau = dTau_;
}

}  // namespace ecm::mpm
