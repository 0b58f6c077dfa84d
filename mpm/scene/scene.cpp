#include "mpm/scene/scene.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "io/value_error.hpp"

namespace ecm::mpm {

namespace {

using io::ValueError;

std::string item(const char* list, std::size_t i) { return std::string(list) + "[" + std::to_string(i) + "]"; }

// A check of a part that throws std::invalid_argument (grid, shape, time function), as a ValueError at `key`.
template <class F>
void check(const std::string& key, F&& f) {
  try {
    f();
  } catch (const ValueError&) {
    throw;
  } catch (const std::invalid_argument& e) {
    throw ValueError(key, e.what());
  }
}

void requireRange(const std::string& key, double v, double lo, double hi, bool loClosed, bool hiClosed) {
  const bool ok = std::isfinite(v) && (loClosed ? v >= lo : v > lo) && (hiClosed ? v <= hi : v < hi);
  if (ok) return;
  std::ostringstream msg;
  msg.precision(10);
  msg << v << " is outside the allowed range " << (loClosed ? "[" : "(") << lo << ", " << hi << (hiClosed ? "]" : ")");
  throw ValueError(key, msg.str());
}

void validateMaterials(const Scene& s) {
  if (s.materials.empty()) throw ValueError("materials", "needs at least one material");
  if (s.materials.size() > 255) throw ValueError("materials", "at most 255 materials");
  // The grid's cells set H (the solver's effective_size rule): its smallest value must be one
  // the enriched point accepts.
  const EffectiveSize cellSize{s.solver.effectiveSize, 0.0, s.grid.cellSize[0], s.grid.cellSize[1]};
  for (std::size_t i = 0; i < s.materials.size(); ++i) {
    const MaterialParams& m = s.materials[i];
    const std::string key = item("materials", i);
    check(key, [&] { m.validate(); });
    if (!(m.density > 0.0)) throw ValueError(key, "material '" + m.name + "': MPM needs density > 0 (t/mm^3)");
    if (m.elastic.hypothesis != s.materials.front().elastic.hypothesis)
      throw ValueError(key, "material '" + m.name + "': all materials must share plane_stress or plane_strain");
    for (std::size_t j = 0; j < i; ++j)
      if (s.materials[j].name == m.name) throw ValueError(key, "material name '" + m.name + "' is defined twice");
    if (m.model == ModelKind::Enriched)
      if (const std::string problem =
              effectiveSizeProblem(cellSize.smallest(), m.bandWidth, m.secondBand == SecondBandOption::Off ? 1 : 2);
          !problem.empty())
        throw ValueError(key, "material '" + m.name + "' on this grid: the cells' " + problem);
  }
}

void validateBodies(const Scene& s) {
  if (s.bodies.empty()) throw ValueError("bodies", "needs at least one body");
  for (std::size_t i = 0; i < s.bodies.size(); ++i) {
    const Body& b = s.bodies[i];
    const std::string key = b.item >= 0 ? item("bodies", static_cast<std::size_t>(b.item)) : item("bodies", i);
    check(key, [&] { b.shape.validate(); });
    if (!b.subtract && (b.material < 0 || b.material >= static_cast<int>(s.materials.size())))
      throw ValueError(key, "material index " + std::to_string(b.material) + " out of range");
    if (!b.initialVelocity.allFinite()) throw ValueError(key + ".initial_velocity", "must be finite");
  }
}

// The implicit settings (docs/implicit.md): ranges, the driven conditions and the control's nodes.
void validateImplicit(const Scene& s) {
  const ImplicitSettings& im = *s.solver.implicit;
  if (s.solver.shapeFunction == ShapeFunction::BSpline2)
    throw ValueError("solver.shape_function",
                     "bspline2 is not offered with implicit_static: quadratic B-splines need a boundary treatment at held "
                     "edges that this code does not have (a held bar's stresses oscillate next to its ends, and it cracks "
                     "there at 1.12 MPa instead of its 2.9 MPa); use linear or ugimp");
  requireRange("solver.tolerance", im.tolerance, 0.0, 1e-2, false, true);
  requireRange("solver.max_iterations", im.maxIterations, 1.0, 500.0, true, true);
  requireRange("solver.max_halvings", im.maxHalvings, 0.0, 30.0, true, true);
  requireRange("solver.onset_overshoot", im.onsetOvershoot, 0.0, 1.0, false, true);
  requireRange("solver.accept_tolerance", im.acceptTolerance, im.tolerance, 1e-2, true, true);
  requireRange("solver.stabilization", im.stabilization, 0.0, 1.0, true, true);
  if (!available(im.linearSolver))
    throw ValueError("solver.linear_solver", im.linearSolver == LinearSolverKind::Amg
                                                 ? "this build has no hypre (libhypre-dev); use umfpack or sparselu"
                                                 : "this build has no UMFPACK (libsuitesparse-dev); use sparselu");
  if (!im.indirect) {
    requireRange("solver.load_step", im.loadStep, 0.0, s.endTime, false, true);
    return;
  }
  const auto& c = *im.indirect;
  if (c.driven.empty()) throw ValueError("solver.control.indirect.driven", "names no condition");
  for (const std::string& name : c.driven)
    if (!findCondition(s.conditions, name) &&
        std::none_of(s.platens.begin(), s.platens.end(), [&](const Platen& p) { return p.name == name; }))
      throw ValueError("solver.control.indirect.driven", "no condition or platen named '" + name + "'");
  for (const Platen& p : s.platens)
    if (std::find(c.driven.begin(), c.driven.end(), p.name) != c.driven.end() && !displacementDriven(p, kPlatenX) && !displacementDriven(p, kPlatenY))
      throw ValueError("solver.control.indirect.driven", "platen '" + p.name + "' has no displacement-driven x or y for the load factor to move");
  if (!c.reference.allFinite() || c.reference.squaredNorm() == 0.0)
    throw ValueError("solver.control.indirect.reference", "must be finite and not zero (mm per unit load factor)");
  if (!c.gauge.empty() && std::none_of(s.gauges.begin(), s.gauges.end(), [&](const Gauge& g) { return g.name == c.gauge; }))
    throw ValueError("solver.control.indirect.gauge", "no gauge is named '" + c.gauge + "'");
  if (c.gauge.empty() && c.terms.empty()) throw ValueError("solver.control.indirect.opening", "names no node");
  bool anyCoefficient = false;
  for (std::size_t i = 0; i < c.terms.size(); ++i) {
    const Vec2 local = (c.terms[i].at - s.grid.origin).cwiseQuotient(s.grid.cellSize);
    if (!(local.minCoeff() >= -0.5 && local[0] <= s.grid.cellsX + 0.5 && local[1] <= s.grid.cellsY + 0.5))
      throw ValueError(item("solver.control.indirect.opening", i), "the node is outside the grid");
    // A term acts on one grid node: a point between nodes is a typing error, not a request to
    // interpolate (1e-6 of a cell allows the decimals of a hand-written coordinate).
    const Vec2 nearest(std::round(local[0]), std::round(local[1]));
    if ((local - nearest).cwiseAbs().maxCoeff() > 1e-6) {
      std::ostringstream msg;
      msg << "(" << c.terms[i].at[0] << ", " << c.terms[i].at[1] << ") mm is not a grid node (the nearest is ("
          << s.grid.origin[0] + nearest[0] * s.grid.cellSize[0] << ", " << s.grid.origin[1] + nearest[1] * s.grid.cellSize[1]
          << ") mm)";
      throw ValueError(item("solver.control.indirect.opening", i) + ".node", msg.str());
    }
    if (!std::isfinite(c.terms[i].coefficient)) throw ValueError(item("solver.control.indirect.opening", i), "coefficient must be finite");
    anyCoefficient = anyCoefficient || c.terms[i].coefficient != 0.0;
  }
  if (c.gauge.empty() && !anyCoefficient)
    throw ValueError("solver.control.indirect.opening", "every coefficient is 0: the opening would not move whatever the displacements");
  requireRange("solver.control.indirect.step", c.step, 0.0, INFINITY, false, false);
  requireRange("solver.control.indirect.until", c.until, c.step, INFINITY, true, false);
  requireRange("solver.control.indirect.from", c.from, 0.0, s.endTime, true, true);
  if (c.from > 0.0) requireRange("solver.load_step", im.loadStep, 0.0, c.from, false, true);
}

void validateSolver(const Scene& s) {
  const SolverSettings& v = s.solver;
  if (v.implicit) validateImplicit(s);
  requireRange("particles_per_cell", s.particlesPerCell, 1.0, 8.0, true, true);
  const ExplicitSettings& e = v.explicitScheme;
  requireRange("solver.flip", e.flip, 0.0, 1.0, true, true);
  requireRange("solver.cfl", e.cfl, 0.0, 1.0, false, true);  // beyond 1 the explicit step is unstable
  requireRange("solver.local_damping", e.damping.local, 0.0, 1.0, true, false);
  requireRange("solver.viscous_damping", e.damping.viscous, 0.0, INFINITY, true, false);
  if (!v.gravity.allFinite()) throw ValueError("solver.gravity", "must be finite");
  if (v.effectiveSize == EffectiveSizeRule::Fixed) throw ValueError("solver.effective_size", "must be sqrt or oriented");
  requireRange("solver.substep_levels", v.substepLevels, 0.0, 12.0, true, true);
  if (v.shapeFunction == ShapeFunction::UGimp && (s.grid.cellsX < 2 || s.grid.cellsY < 2))
    throw ValueError("solver.shape_function", "uGIMP needs at least 2 cells in x and y");
}

void validateOutput(const Scene& s) {
  requireRange("end_time", s.endTime, 0.0, INFINITY, false, false);
  requireRange("output_interval", s.outputInterval, 0.0, INFINITY, true, false);
  if (s.snapshotEvery < 1) throw ValueError("snapshot_every", "must be >= 1");
  for (std::size_t i = 0; i < s.particleSnapshots.size(); ++i) {
    requireRange(item("particle_snapshots", i), s.particleSnapshots[i], 0.0, INFINITY, false, false);
    if (i > 0 && !(s.particleSnapshots[i] > s.particleSnapshots[i - 1]))
      throw ValueError("particle_snapshots", "times must increase");
    if (s.particleSnapshots[i] > s.endTime) throw ValueError("particle_snapshots", "a time after end_time");
  }
  if (s.checkpoint.everySteps < 0 || s.checkpoint.everySteps > 2147483647L)
    throw ValueError("checkpoint.every_steps", "must be >= 1 (0: off)");
  requireRange("checkpoint.every_minutes", s.checkpoint.everyMinutes, 0.0, INFINITY, true, false);
  for (std::size_t i = 0; i < s.gauges.size(); ++i) {
    const Gauge& g = s.gauges[i];
    if (g.name.empty()) throw ValueError(item("gauges", i) + ".name", "must not be empty");
    for (std::size_t j = 0; j < i; ++j)
      if (s.gauges[j].name == g.name) throw ValueError(item("gauges", i) + ".name", "'" + g.name + "' is defined twice");
    if (!g.at.allFinite() || (g.to && !g.to->allFinite())) throw ValueError(item("gauges", i), "its points must be finite");
    if (g.to && *g.to == g.at) throw ValueError(item("gauges", i) + ".to", "is the same point as at: the gauge would read 0");
  }
  if (s.stopWhen && !s.stopWhen->gauge.empty()) {
    const StopWhen& w = *s.stopWhen;
    if (std::none_of(s.gauges.begin(), s.gauges.end(), [&](const Gauge& g) { return g.name == w.gauge; }))
      throw ValueError("stop_when.gauge", "no gauge is named '" + w.gauge + "'");
    requireRange("stop_when.reaches", w.gaugeReaches, 0.0, INFINITY, false, false);
    requireRange("stop_when.after_time", w.afterTime, 0.0, INFINITY, true, false);
    if (!(s.outputInterval > 0.0) && !s.solver.implicit)  // implicit runs have a row per load step
      throw ValueError("stop_when", "is checked at the output rows: needs output_interval > 0");
  } else if (s.stopWhen) {
    const StopWhen& w = *s.stopWhen;
    if (!findCondition(s.conditions, w.condition))
      throw ValueError("stop_when.condition", "no condition is named '" + w.condition + "'");
    requireRange("stop_when.load_below", w.loadBelow, 0.0, 1.0, false, false);
    requireRange("stop_when.after_time", w.afterTime, 0.0, INFINITY, true, false);
    // Implicit runs under indirect control watch their progress: the pseudo-time to `from`, then
    // `from` plus the opening (mm) (docs/implicit.md).
    const auto& implicit = s.solver.implicit;
    const double end = implicit && implicit->indirect ? implicit->indirect->from + implicit->indirect->until : s.endTime;
    if (!(w.afterTime < end))
      throw ValueError("stop_when", "after_time is not before end_time (under indirect control: from + until): it would never stop the run");
    if (!(s.outputInterval > 0.0) && !s.solver.implicit)  // implicit runs have a row per load step
      throw ValueError("stop_when", "is checked at the output rows: needs output_interval > 0");
  }
}

void validateBox(const std::string& key, const Box& b) {
  if (!(b.min.allFinite() && b.max.allFinite())) throw ValueError(key, "must be finite");
  if (!(b.max[0] >= b.min[0] && b.max[1] >= b.min[1])) throw ValueError(key, "box needs max >= min in x and y");
}

void validateConditions(const Scene& s) {
  const Grid& g = s.grid;
  for (std::size_t i = 0; i < s.conditions.size(); ++i) {
    const NodeCondition& c = s.conditions[i];
    const std::string key = item("conditions", i);
    validateBox(key + ".box", c.box);
    bool any = false;
    const double tol = 1e-9 * std::min(g.cellSize[0], g.cellSize[1]);
    for (int n = 0; n < g.nodeCount() && !any; ++n) any = c.box.contains(g.nodePosition(n), tol);
    if (!any) throw ValueError(key + ".box", "contains no grid node");
    for (int d = 0; d < 2; ++d) {
      const ComponentCondition& k = c.component[static_cast<std::size_t>(d)];
      if (k.kind != Prescribed::Velocity && k.kind != Prescribed::Displacement) continue;
      const std::string what = k.kind == Prescribed::Velocity ? ".velocity." : ".displacement.";
      check(key + what + (d ? "y" : "x"), [&] { k.history.validate(); });
    }
    if (c.field) {
      if (c.component[0].kind != Prescribed::Free || c.component[1].kind != Prescribed::Free)
        throw ValueError(key + ".velocity_field", "cannot be combined with fixed, velocity or displacement");
      check(key + ".velocity_field.scale", [&] { c.field->scale.validate(); });
      if (!c.field->gradient.allFinite()) throw ValueError(key + ".velocity_field.gradient", "must be finite");
      if (!c.field->origin.allFinite()) throw ValueError(key + ".velocity_field.origin", "must be finite");
    }
    if (!c.field && c.component[0].kind == Prescribed::Free && c.component[1].kind == Prescribed::Free)
      throw ValueError(key, "condition '" + c.name + "' prescribes nothing (give fixed, velocity, displacement or velocity_field)");
  }
  for (std::size_t i = 0; i < s.loads.size(); ++i) {
    const Load& l = s.loads[i];
    const std::string key = item("loads", i);
    validateBox(key + ".box", l.box);
    if (!l.force.allFinite()) throw ValueError(key + ".force", "must be finite");
    check(key + ".history", [&] { l.history.validate(); });
  }
}

// Platens (mpm/scene/platen.hpp): names unique among platens and conditions, boxes with grid
// nodes, histories sound. What needs the nodes themselves (a rotation on one node, a node of
// two platens or of a platen and a condition) is checked where they are found (platenStates).
void validatePlatens(const Scene& s) {
  const Grid& g = s.grid;
  const double tol = 1e-9 * std::min(g.cellSize[0], g.cellSize[1]);
  for (std::size_t i = 0; i < s.platens.size(); ++i) {
    const Platen& p = s.platens[i];
    const std::string key = item("platens", i);
    if (p.name.empty()) throw ValueError(key + ".name", "must not be empty");
    for (std::size_t j = 0; j < i; ++j)
      if (s.platens[j].name == p.name) throw ValueError(key + ".name", "'" + p.name + "' is defined twice");
    if (findCondition(s.conditions, p.name)) throw ValueError(key + ".name", "'" + p.name + "' is also a condition's name");
    for (std::size_t b = 0; b < p.boxes.size(); ++b) {
      const std::string boxKey = item((key + ".boxes").c_str(), b);
      validateBox(boxKey, p.boxes[b]);
      bool any = false;
      for (int n = 0; n < g.nodeCount() && !any; ++n) any = p.boxes[b].contains(g.nodePosition(n), tol);
      if (!any) throw ValueError(boxKey, "contains no grid node");
    }
    if (p.reference && !p.reference->allFinite()) throw ValueError(key + ".reference", "must be finite");
    // Its nodes: none shared with a condition or an earlier platen; two or more to carry a rotation.
    int nodes = 0;
    for (int n = 0; n < g.nodeCount(); ++n) {
      const Vec2 x = g.nodePosition(n);
      const auto inside = [&](const Box& b) { return b.contains(x, tol); };
      if (std::none_of(p.boxes.begin(), p.boxes.end(), inside)) continue;
      ++nodes;
      const auto clash = [&](const std::string& what) {
        std::ostringstream msg;
        msg << "its node at (" << x[0] << ", " << x[1] << ") mm also belongs to " << what << " (a node moves with one platen or condition)";
        throw ValueError(key + ".boxes", msg.str());
      };
      for (const NodeCondition& c : s.conditions)
        if (inside(c.box)) clash("condition '" + c.name + "'");
      for (std::size_t j = 0; j < i; ++j)
        if (std::any_of(s.platens[j].boxes.begin(), s.platens[j].boxes.end(), inside)) clash("platen '" + s.platens[j].name + "'");
    }
    if (nodes < 2 && p.dof[kPlatenRotation].drive != PlatenDrive::Held)
      throw ValueError(key + ".rotation", "must be held on a platen of one node (a rotation needs two nodes or more)");
    const char* names[3] = {"x", "y", "rotation"};
    for (int d = 0; d < 3; ++d) {
      const PlatenDof& dof = p.dof[static_cast<std::size_t>(d)];
      if (dof.drive == PlatenDrive::Displacement || dof.drive == PlatenDrive::Force)
        check(key + "." + names[d], [&] { dof.history.validate(); });
      requireRange(key + "." + names[d] + ".free_until", dof.freeUntil, 0.0, INFINITY, true, false);
    }
  }
}

}  // namespace

// The one check of a scene's values (the YAML reader checks only the form of the file and
// reports these at their lines, mpm/scene/scene_yaml.cpp).
void Scene::validate() const {
  check("grid", [&] { grid.validate(); });
  requireRange("thickness", thickness, 0.0, INFINITY, false, false);
  validateMaterials(*this);
  validateBodies(*this);
  validateSolver(*this);
  validateOutput(*this);
  validateConditions(*this);
  validatePlatens(*this);
}

}  // namespace ecm::mpm
