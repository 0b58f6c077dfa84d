// A converged load step committed (mpm/implicit/implicit_solver.hpp): the particles moved and
// their states kept, the reactions, the platens' motion and forces, the step's works.
#include "mpm/implicit/implicit_solver.hpp"

namespace ecm::mpm {

double ImplicitSolver::commit(const Attempt& a, double dt) {
  const Scene& scene = setup_.scene;
  const Trial& t = a.trial;
  Particles& p = particles_;
  const int nx = scene.grid.nodesX(), support = supportSize(scene.solver.shapeFunction);
  double internal = 0.0;
  // A stabilised step: the energy its dashpots took, what a dynamic jump would have turned into
  // kinetic energy (docs/implicit.md, "Stabilised steps"): its external work less what the strain
  // energy gained and the materials dissipated.
  const bool stabilized = a.report.proximalSteps > 0;
  double strainChange = 0.0, dissipatedInStep = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (stabilized) {
      strainChange += 0.5 * p.volume[i] * (t.stress[i].dot(t.strain[i]) - p.stress[i].dot(p.strain[i]));
      dissipatedInStep += p.volume[i] * t.dissipation[i];
    }
    const Stencil& s = geometry_.stencils[i];
    Vec2 move = Vec2::Zero();
    for (int j = 0; j < support; ++j)
      for (int k = 0; k < support; ++k) move += s.wx[k] * s.wy[j] * a.du.segment<2>(2 * static_cast<Eigen::Index>(s.base + j * nx + k));
    p.position[i] += move;
    internal += 0.5 * p.volume[i] * (p.stress[i] + t.stress[i]).dot(t.strain[i] - p.strain[i]);
    p.strain[i] = t.strain[i];
    p.stress[i] = t.stress[i];
    if (t.band[i]) {
      if (p.band[i] < 0) {
        p.band[i] = static_cast<std::int32_t>(p.bands.size());
        p.bands.push_back(*t.band[i]);
      } else {
        p.bands[static_cast<std::size_t>(p.band[i])] = *t.band[i];
      }
    }
    if (t.secondBand[i] && !p.secondBand.empty()) {
      if (p.secondBand[i] < 0) {
        p.secondBand[i] = static_cast<std::int32_t>(p.secondBands.size());
        p.secondBands.push_back(*t.secondBand[i]);
      } else {
        p.secondBands[static_cast<std::size_t>(p.secondBand[i])] = *t.secondBand[i];
      }
    }
    totals_.dissipated += p.volume[i] * t.dissipation[i];
  }
  if (!t.integrity.empty()) p.integrity = t.integrity;
  // Reactions: what the constraints add to the loads to balance the internal forces (a tied
  // node's unbalanced force belongs to its sources: T^T).
  Eigen::VectorXd unbalanced = t.internalForce - a.external;
  transferTies(a.ties, unbalanced);
  for (std::size_t c = 0; c < conditions_.size(); ++c) {
    ConditionState& state = conditions_[c];
    const NodeCondition& cond = scene.conditions[c];
    state.reaction.setZero();
    for (const std::int32_t node : state.nodes)
      for (int d = 0; d < 2; ++d)
        if (a.prescribed[2 * static_cast<std::size_t>(node) + static_cast<std::size_t>(d)])
          state.reaction[d] += unbalanced[2 * node + d];
    for (int d = 0; d < 2; ++d) {
      const ComponentCondition& k = cond.component[static_cast<std::size_t>(d)];
      if (cond.field) continue;
      if (!state.nodes.empty() && a.direction.size() > 0 && a.direction[2 * state.nodes[0] + d] != 0.0) {
        state.displacement[d] += a.dLambda * a.direction[2 * state.nodes[0] + d];  // driven by the load factor
        continue;
      }
      if (k.kind == Prescribed::Displacement) state.displacement[d] = k.history(time_ + dt);
      if (k.kind == Prescribed::Velocity) state.displacement[d] += dt * k.history(time_ + dt);
    }
  }
  // The works of the step, trapezoidal (docs/implicit.md, "Energies"): the external work of the
  // forces the loads and the constraints apply (at a prescribed component the internal force, at a
  // free one the load), and the internal work sum_p V (sigma_n + sigma_n+1)/2 : d eps_p.
  // They differ by the work of the residual: the check of equilibrium in energy.
  // A tied node's forces are its sources' (T^T) and its increment theirs: it is skipped.
  double external = 0.0;
  {
    Eigen::VectorXd startForce = a.startForce, endForce = t.internalForce, loadStart = a.externalStart, load = a.external;
    std::vector<std::uint8_t> tied;
    if (!a.ties.empty()) {
      for (Eigen::VectorXd* v : {&startForce, &endForce, &loadStart, &load}) transferTies(a.ties, *v);
      tied.assign(static_cast<std::size_t>(a.du.size()), 0);
      for (const NodeTie& tie : a.ties) tied[2 * static_cast<std::size_t>(tie.node)] = tied[2 * static_cast<std::size_t>(tie.node) + 1] = 1;
    }
    for (Eigen::Index k = 0; k < a.du.size(); ++k) {
      if (a.du[k] == 0.0 || (!tied.empty() && tied[static_cast<std::size_t>(k)])) continue;
      const bool held = geometry_.dofs.unknownOf[static_cast<std::size_t>(k)] == DofMap::kPrescribed;
      external += 0.5 * (held ? startForce[k] + endForce[k] : loadStart[k] + load[k]) * a.du[k];
    }
  }
  // The platens: where they went (the prescribed increments, and the rest fitted to their nodes'
  // increments, which move rigidly), what they put on the specimen (sum_k B_k^T (f_int - f_ext)
  // over their nodes, plus their force histories, which f_ext holds spread over the nodes) and the
  // work of their prescribed degrees of freedom (the rest is in the nodes' loads above).
  for (std::size_t p = 0; p < platens_.size(); ++p) {
    PlatenState& state = platens_[p];
    const Platen& platen = scene.platens[p];
    Eigen::Matrix3d sum = Eigen::Matrix3d::Zero();
    Eigen::Vector3d fit = Eigen::Vector3d::Zero(), onSpecimen = Eigen::Vector3d::Zero(), atStart = Eigen::Vector3d::Zero();
    for (const std::int32_t node : state.nodes) {
      const Eigen::Matrix<double, 2, 3> b = rigidMap(scene.grid.nodePosition(node), state.reference);
      const Eigen::Index k = 2 * static_cast<Eigen::Index>(node);
      onSpecimen += b.transpose() * (t.internalForce.segment<2>(k) - a.external.segment<2>(k));
      if (a.startForce.size() > 0) atStart += b.transpose() * (a.startForce.segment<2>(k) - a.externalStart.segment<2>(k));
      if (!geometry_.reached[static_cast<std::size_t>(k)]) continue;
      sum += b.transpose() * b;
      fit += b.transpose() * a.du.segment<2>(k);
    }
    const Eigen::Vector3d rigid = solveRigid(sum, fit);
    for (int d = 0; d < 3; ++d) {
      const PlatenDof& dof = platen.dof[static_cast<std::size_t>(d)];
      const bool prescribed = a.platenPrescribed[p][static_cast<std::size_t>(d)];
      const double increment = prescribed ? a.platenIncrement[p][d] + a.dLambda * a.platenDirection[p][d] : rigid[d];
      if (dof.drive == PlatenDrive::Force) {
        onSpecimen[d] += dof.history(time_ + dt);
        atStart[d] += dof.history(time_);
      }
      if (prescribed) external += 0.5 * (atStart[d] + onSpecimen[d]) * increment;
      state.displacement[d] += increment;
    }
    state.force = onSpecimen;
  }
  totals_.externalWork += external;
  internalWork_ += internal;
  totals_.released += a.releases();
  const double dashpotWork = stabilized ? external - strainChange - dissipatedInStep : 0.0;
  totals_.damping += dashpotWork;
  if (a.dTau != 0.0) lastIncrement_ = {a.du, a.dLambda, a.dTau};
  lambda_ += a.dLambda;
  time_ += dt;
  ++steps_;
  return dashpotWork;
}

}  // namespace ecm::mpm
