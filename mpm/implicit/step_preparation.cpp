// A load step's preparation (mpm/implicit/implicit_solver.hpp): the prescribed components and
// their increments (or, under indirect control, the driven ones' reference), the platens, the
// step's geometry, the weakly reached nodes' ties and the change of unknowns, the loads at the
// step's start and end.
#include <algorithm>
#include <cmath>
#include <utility>

#include "mpm/implicit/implicit_solver.hpp"

namespace ecm::mpm {

namespace {

// The prescribed displacement of a component over [t, t + dt], or NaN when it is free.
double prescribedIncrement(const ComponentCondition& c, double t, double dt) {
  switch (c.kind) {
    case Prescribed::Free: return NAN;
    case Prescribed::Fixed: return 0.0;
    case Prescribed::Velocity: return dt * c.history(t + dt);
    case Prescribed::Displacement: return c.history(t + dt) - c.history(t);
  }
  return NAN;
}

}  // namespace

bool ImplicitSolver::prepare(double dt, const IndirectControl* control, Attempt& a) {
  const Scene& scene = setup_.scene;
  const Grid& grid = scene.grid;
  const double t0 = time_, t1 = time_ + dt;
  const auto components = static_cast<Eigen::Index>(2 * grid.nodeCount());
  // The prescribed components and their increments.
  // (Under indirect control the driven conditions' components follow the load factor instead:
  // their direction is the reference, their increment found by the step.)
  a.prescribed.assign(static_cast<std::size_t>(components), 0);
  a.du.setZero(components);
  a.direction.setZero(components);
  for (std::size_t c = 0; c < scene.conditions.size(); ++c) {
    const NodeCondition& cond = scene.conditions[c];
    const bool driven = control && std::find(control->driven.begin(), control->driven.end(), c) != control->driven.end();
    for (const std::int32_t node : conditions_[c].nodes) {
      Vec2 du(prescribedIncrement(cond.component[0], t0, dt), prescribedIncrement(cond.component[1], t0, dt));
      if (cond.field) du = dt * cond.field->scale(t1) * cond.field->gradient * (grid.nodePosition(node) - cond.field->origin);
      for (int d = 0; d < 2; ++d) {
        if (std::isnan(du[d])) continue;
        a.prescribed[2 * static_cast<std::size_t>(node) + static_cast<std::size_t>(d)] = 1;
        const bool follows = driven && !cond.field && cond.component[static_cast<std::size_t>(d)].kind != Prescribed::Fixed;
        if (follows)
          a.direction[2 * node + d] = control->reference[d];
        else
          a.du[2 * node + d] = du[d];
      }
    }
  }
  // The platens: their nodes' components stay unknowns; the increments of their prescribed
  // degrees of freedom (or, driven by the load factor, their reference) move them rigidly.
  a.platenPrescribed.assign(platens_.size(), {true, true, true});
  a.platenIncrement.assign(platens_.size(), Eigen::Vector3d::Zero());
  a.platenDirection.assign(platens_.size(), Eigen::Vector3d::Zero());
  for (std::size_t p = 0; p < platens_.size(); ++p) {
    const Platen& platen = scene.platens[p];
    const bool driven = control && std::find(control->drivenPlatens.begin(), control->drivenPlatens.end(), p) != control->drivenPlatens.end();
    for (int d = 0; d < 3; ++d) {
      const PlatenDof& dof = platen.dof[static_cast<std::size_t>(d)];
      // (Under indirect control a driven platen's displacements follow the load factor, free_until aside.)
      const bool followsControl = driven && d < 2 && dof.drive == PlatenDrive::Displacement;
      a.platenPrescribed[p][static_cast<std::size_t>(d)] = dof.drive == PlatenDrive::Held || dof.drivenAt(t0) || followsControl;
      if (followsControl)
        a.platenDirection[p][d] = control->reference[d];
      else if (dof.drivenAt(t0))
        a.platenIncrement[p][d] = dof.history(t1) - dof.history(t0);
    }
    for (const std::int32_t node : platens_[p].nodes) {
      const Eigen::Matrix<double, 2, 3> b = rigidMap(grid.nodePosition(node), platens_[p].reference);
      a.du.segment<2>(2 * static_cast<Eigen::Index>(node)) = b * a.platenIncrement[p];
      a.direction.segment<2>(2 * static_cast<Eigen::Index>(node)) = b * a.platenDirection[p];
    }
  }
  // The geometry of the committed state (the pieces of a halved step share it).
  if (geometryStep_ != steps_ || geometry_.prescribed != a.prescribed) {
    std::size_t outside = 0;
    geometryStep_ = -1;
    if (!stepGeometry(setup_, particles_, a.prescribed, geometry_, outside)) {
      a.failedParticle = outside;
      return a.fail(0, 0.0, NewtonFailure::LeftGrid, "its shape-function support left the grid");
    }
    geometryStep_ = steps_;
  }
  geometry_.crackPaths = &crackPaths_;
  // Nodes the body barely reaches: tied to their neighbours (neither a prescribed component nor a
  // platen's node is tied; a platen's node is no source).
  {
    const auto nodes = static_cast<std::size_t>(grid.nodeCount());
    std::vector<std::uint8_t> mayTie(nodes, 1), maySource(nodes, 1);
    for (std::size_t n = 0; n < nodes; ++n) mayTie[n] = !a.prescribed[2 * n] && !a.prescribed[2 * n + 1];
    for (const PlatenState& platen : platens_)
      for (const std::int32_t node : platen.nodes) mayTie[static_cast<std::size_t>(node)] = maySource[static_cast<std::size_t>(node)] = 0;
    a.ties = weakNodeTies(grid.nodesX(), grid.nodesY(), geometry_.share, mayTie, maySource);
  }
  a.reduction.reset();
  if (!platens_.empty() || !a.ties.empty()) {
    a.reduction = unknownReduction(scene, platens_, geometry_.dofs, a.platenPrescribed, a.ties);
    if (a.platenPrescribed != platenLayout_ || a.ties != tieLayout_)  // a factorisation of other unknowns
      platenLayout_ = a.platenPrescribed, tieLayout_ = a.ties, ++reductionLayouts_;
    applyTies(a.ties, a.du);  // a prescribed source's increment (the others are 0 here)
    applyTies(a.ties, a.direction);
  }
  // Loads and gravity at the step's start and end.
  const int nx = grid.nodesX(), support = supportSize(scene.solver.shapeFunction);
  const auto spread = [&](Eigen::VectorXd& into, const Stencil& s, const Vec2& f) {
    for (int j = 0; j < support; ++j)
      for (int k = 0; k < support; ++k) {
        const Eigen::Index n = s.base + j * nx + k;
        into.segment<2>(2 * n) += s.wx[k] * s.wy[j] * f;
      }
  };
  for (const auto& [into, t] : {std::pair<Eigen::VectorXd*, double>{&a.externalStart, t0}, {&a.external, t1}}) {
    into->setZero(components);
    if (scene.solver.gravity.squaredNorm() > 0.0)
      for (std::size_t i = 0; i < particles_.size(); ++i) spread(*into, geometry_.stencils[i], particles_.mass[i] * scene.solver.gravity);
    for (std::size_t l = 0; l < scene.loads.size(); ++l) {
      const Load& load = scene.loads[l];
      const Vec2 each = load.force * load.history(t) / static_cast<double>(loads_[l].members.size());
      for (const std::int32_t m : loads_[l].members) {
        if (load.target == LoadTarget::Nodes)
          into->segment<2>(2 * static_cast<Eigen::Index>(m)) += each;
        else
          spread(*into, geometry_.stencils[static_cast<std::size_t>(m)], each);
      }
    }
    // A platen's force histories, spread over its nodes that carry the body so that their
    // generalized force is the history's: f_k = B_k A^-1 F with A = sum_k B_k^T B_k.
    for (std::size_t p = 0; p < platens_.size(); ++p) {
      Eigen::Vector3d force = Eigen::Vector3d::Zero();
      for (int d = 0; d < 3; ++d)
        if (scene.platens[p].dof[static_cast<std::size_t>(d)].drive == PlatenDrive::Force)
          force[d] = scene.platens[p].dof[static_cast<std::size_t>(d)].history(t);
      if (force.isZero()) continue;
      Eigen::Matrix3d sum = Eigen::Matrix3d::Zero();
      for (const std::int32_t node : platens_[p].nodes)
        if (geometry_.reached[2 * static_cast<std::size_t>(node)]) {
          const Eigen::Matrix<double, 2, 3> b = rigidMap(grid.nodePosition(node), platens_[p].reference);
          sum += b.transpose() * b;
        }
      const Eigen::Vector3d each = solveRigid(sum, force);
      for (const std::int32_t node : platens_[p].nodes)
        if (geometry_.reached[2 * static_cast<std::size_t>(node)])
          into->segment<2>(2 * static_cast<Eigen::Index>(node)) += rigidMap(grid.nodePosition(node), platens_[p].reference) * each;
    }
  }
  return true;
}

}  // namespace ecm::mpm
