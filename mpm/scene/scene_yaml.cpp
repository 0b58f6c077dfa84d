#include "mpm/scene/scene_yaml.hpp"

#include <algorithm>
#include <map>

#include "io/material_yaml.hpp"
#include "io/value_error.hpp"
#include "mpm/scene/memory_estimate.hpp"
#include "mpm/scene/presets.hpp"

namespace ecm::mpm {

namespace {

using io::InputError;
using io::Range;
using io::YamlMap;

int lineOf(const YAML::Node& n, int fallback) {
  const YAML::Mark m = n.Mark();
  return m.is_null() || m.line < 0 ? fallback : m.line + 1;
}

Vec2 vec2(const YamlMap& m, const std::string& key, const Range& r = Range::any()) {
  const auto v = m.getVector(key, 2, r);
  return {v[0], v[1]};
}

// A sequence of [a, b] pairs (polygon vertices, table points, matrix rows).
std::vector<Vec2> pairs(const YamlMap& m, const std::string& key, std::size_t minCount) {
  if (!m.has(key)) m.fail(key, "is required");
  const YAML::Node seq = m.node()[key];
  const int line = m.line(key);
  if (!seq.IsSequence() || seq.size() < minCount)
    m.fail(key, "expected a sequence of at least " + std::to_string(minCount) + " [a, b] pairs");
  std::vector<Vec2> out;
  for (std::size_t i = 0; i < seq.size(); ++i) {
    const YAML::Node p = seq[i];
    const int l = lineOf(p, line);
    const std::string where = "key '" + (m.path().empty() ? key : m.path() + "." + key) + "[" + std::to_string(i) + "]'";
    if (!p.IsSequence() || p.size() != 2) throw InputError(m.file(), l, where + ": expected a pair [a, b]");
    Vec2 v;
    for (std::size_t c = 0; c < 2; ++c) {
      try {
        v[static_cast<int>(c)] = p[c].as<double>();
      } catch (const YAML::Exception&) {
        throw InputError(m.file(), l, where + ": expected numbers");
      }
      if (!std::isfinite(v[static_cast<int>(c)])) throw InputError(m.file(), l, where + ": expected finite numbers");
    }
    out.push_back(v);
  }
  return out;
}

TimeFunction readTimeFunction(const YamlMap& m) {
  const std::string type = m.getEnum("type", {"hold", "linear_ramp", "smooth_ramp", "table"});
  TimeFunction h;
  if (type == "table") {
    for (const Vec2& p : pairs(m, "points", 1)) {
      h.times.push_back(p[0]);
      h.values.push_back(p[1]);
    }
    h.kind = TimeFunctionKind::Table;
  } else {
    h.value = m.get<double>("value");
    if (type != "hold") h.rampTime = m.get<double>("time");
    h.kind = type == "hold" ? TimeFunctionKind::Hold : (type == "linear_ramp" ? TimeFunctionKind::LinearRamp : TimeFunctionKind::SmoothRamp);
  }
  return h;
}

Box readBox(const YamlMap& m) { return {vec2(m, "min"), vec2(m, "max")}; }

Grid readGrid(const YamlMap& m) {
  Grid g;
  g.origin = vec2(m, "origin");
  g.cellSize = vec2(m, "cell_size");
  const auto cells = m.getVector("cells", 2, Range{1.0, 1e9, true, true});  // whole numbers that fit an int
  if (cells[0] != std::floor(cells[0]) || cells[1] != std::floor(cells[1])) m.fail("cells", "expected whole numbers");
  g.cellsX = static_cast<int>(cells[0]);
  g.cellsY = static_cast<int>(cells[1]);
  return g;
}

std::string presetOwns(const std::string& preset) {
  return "set by preset '" + preset + "' (mpm/scene/presets.hpp); remove the preset or this key";
}

// The implicit part of solver: {scheme: implicit_static, ...} (the defaults: ImplicitSettings).
ImplicitSettings readImplicitSettings(const YamlMap& m) {
  ImplicitSettings im;
  im.tolerance = m.getOr<double>("tolerance", im.tolerance);
  im.maxIterations = m.getOr<int>("max_iterations", im.maxIterations);
  im.maxHalvings = m.getOr<int>("max_halvings", im.maxHalvings);
  im.onsetOvershoot = m.getOr<double>("onset_overshoot", im.onsetOvershoot);
  im.acceptTolerance = m.getOr<double>("accept_tolerance", std::max(im.acceptTolerance, im.tolerance));
  im.stabilization = m.getOr<double>("stabilization", im.stabilization);
  im.linearSolver = m.getEnumOr("linear_solver", std::array{LinearSolverKind::Umfpack, LinearSolverKind::SparseLU, LinearSolverKind::Amg},
                                im.linearSolver);
  if (m.has("control")) {
    const YamlMap c = m.child("control");
    const YamlMap i = c.child("indirect");
    ImplicitSettings::Indirect ind;
    ind.driven = i.scalarSequence<std::string>("driven");
    if (i.has("reference")) ind.reference = vec2(i, "reference");
    if (i.has("opening") == i.has("gauge")) i.failHere("control.indirect needs exactly one of opening: [...] and gauge: NAME");
    if (i.has("gauge")) ind.gauge = i.get<std::string>("gauge");
    if (i.has("opening")) {
      for (const YamlMap& t : i.sequence("opening")) {
        ControlTerm term;
        term.at = vec2(t, "node");
        term.component = t.getEnum("component", {"x", "y"}) == "x" ? 0 : 1;
        term.coefficient = t.getOr<double>("coefficient", 1.0);
        t.finish();
        ind.terms.push_back(term);
      }
    }
    ind.step = i.get<double>("step");
    ind.until = i.get<double>("until");
    ind.from = i.getOr<double>("from", 0.0);
    i.finish();
    c.finish();
    im.indirect = ind;
    if (ind.from > 0.0)
      im.loadStep = m.get<double>("load_step");  // the steps of pseudo-time before `from`
    else
      m.reject("load_step", "is set by the indirect control's step (load_step goes with control.indirect.from > 0)");
  } else {
    im.loadStep = m.get<double>("load_step");
  }
  return im;
}

// The explicit part of solver: {scheme: usf | usl | musl, ...} (the defaults: ExplicitSettings).
ExplicitSettings readExplicitSettings(const YamlMap& m, const std::string& scheme) {
  ExplicitSettings e;
  e.scheme = scheme == "usf" ? UpdateScheme::USF : (scheme == "musl" ? UpdateScheme::MUSL : UpdateScheme::USL);
  e.flip = m.getOr<double>("flip", e.flip);
  e.cfl = m.getOr<double>("cfl", e.cfl);
  e.damping.local = m.getOr<double>("local_damping", e.damping.local);
  e.damping.viscous = m.getOr<double>("viscous_damping", e.damping.viscous);
  return e;
}

// solver: the keys both solvers read, once; then the scheme's own part, the other scheme's keys refused.
SolverSettings readSolver(const YamlMap& m, const std::string& preset) {
  if (!preset.empty())
    for (const char* k : {"shape_function", "scheme", "cfl"}) m.reject(k, presetOwns(preset));
  SolverSettings s;
  const std::string scheme = m.getEnumOr("scheme", {"usf", "usl", "musl", "implicit_static"}, toString(ExplicitSettings{}.scheme));
  s.shapeFunction = m.getEnumOr("shape_function", std::array{ShapeFunction::Linear, ShapeFunction::UGimp, ShapeFunction::BSpline2},
                                s.shapeFunction);
  s.effectiveSize = m.getEnumOr("effective_size", std::array{EffectiveSizeRule::SquareRoot, EffectiveSizeRule::Oriented}, s.effectiveSize);
  if (m.has("gravity")) s.gravity = vec2(m, "gravity");
  s.substepLevels = m.getOr<int>("substep_levels", s.substepLevels);
  s.snapBack = io::readSnapBackPolicy(m);
  s.crackPath = m.getEnumOr("crack_path", std::array{CrackPathRule::Tracked, CrackPathRule::Free}, s.crackPath);
  if (scheme == "implicit_static") {
    for (const char* k : {"flip", "cfl", "local_damping", "viscous_damping"})
      m.reject(k, "is a key of explicit scenes (implicit_static has no time step, mass or damping)");
    s.implicit = readImplicitSettings(m);
  } else {
    for (const char* k : {"tolerance", "max_iterations", "max_halvings", "onset_overshoot", "accept_tolerance", "stabilization", "load_step", "control",
                          "linear_solver"})
      m.reject(k, "is a key of implicit_static scenes (this one is explicit)");
    s.explicitScheme = readExplicitSettings(m, scheme);
  }
  return s;
}

int materialIndex(const YamlMap& m, const std::string& key, const std::map<std::string, int>& materials) {
  const std::string name = m.get<std::string>(key);
  const auto it = materials.find(name);
  if (it == materials.end()) {
    std::string known;
    for (const auto& [k, v] : materials) known += (known.empty() ? "" : ", ") + k;
    m.fail(key, "unknown material '" + name + "' (defined: " + known + ")");
  }
  return it->second;
}

Body readBody(const YamlMap& m, const std::map<std::string, int>& materials) {
  Body b;
  const int shapes = int(m.has("rectangle")) + int(m.has("polygon")) + int(m.has("circle"));
  if (shapes != 1) m.failHere("a body needs exactly one of rectangle, polygon, circle");
  if (m.has("rectangle")) {
    const YamlMap r = m.child("rectangle");
    b.shape = Shape::rectangle(vec2(r, "min"), vec2(r, "max"));
  } else if (m.has("circle")) {
    const YamlMap c = m.child("circle");
    b.shape = Shape::circle(vec2(c, "center"), c.get<double>("radius"));
  } else {
    b.shape = Shape::polygon(pairs(m, "polygon", 3));
  }
  b.subtract = m.getOr<bool>("subtract", false);
  if (b.subtract) {
    m.reject("material", "a subtracting body has no material");
    m.reject("initial_velocity", "a subtracting body has no particles");
    return b;
  }
  b.material = materialIndex(m, "material", materials);
  if (m.has("initial_velocity")) b.initialVelocity = vec2(m, "initial_velocity");
  return b;
}

// An `rve:` body: the sample generated here, expanded into matrix, ITZ and inclusion bodies.
std::vector<Body> readRveBody(const YamlMap& m, const std::map<std::string, int>& materials) {
  const YamlMap r = m.child("rve");
  const RveParams p = readRveParams(r);
  const int matrix = materialIndex(r, "matrix", materials);
  const int inclusion = materialIndex(r, "inclusion", materials);
  const int itz = materialIndex(r, "itz", materials);
  try {
    return rveBodies(generateRve(p), matrix, inclusion, itz);
  } catch (const RveInfeasible& e) {
    r.failHere(e.what());
  }
}

NodeCondition readCondition(const YamlMap& m) {
  NodeCondition c;
  c.name = m.get<std::string>("name");
  c.box = readBox(m.child("box"));
  auto set = [&](int d, Prescribed kind, const TimeFunction& h, const std::string& key) {
    auto& k = c.component[static_cast<std::size_t>(d)];
    if (k.kind != Prescribed::Free) m.fail(key, std::string("component ") + (d ? "y" : "x") + " is prescribed twice");
    k = {kind, h};
  };
  if (m.has("fixed")) {
    for (const std::string& s : m.scalarSequence<std::string>("fixed")) {
      if (s != "x" && s != "y") m.fail("fixed", "expected components x and/or y, got '" + s + "'");
      set(s == "y", Prescribed::Fixed, {}, "fixed");
    }
  }
  for (const auto& [key, kind] : {std::pair{"velocity", Prescribed::Velocity}, std::pair{"displacement", Prescribed::Displacement}}) {
    if (!m.has(key)) continue;
    const YamlMap v = m.child(key);
    bool some = false;
    for (int d = 0; d < 2; ++d) {
      const std::string comp = d ? "y" : "x";
      if (!v.has(comp)) continue;
      set(d, kind, readTimeFunction(v.child(comp)), key);
      some = true;
    }
    if (!some) {
      v.finish();  // an unknown component key says more than "nothing given"
      m.fail(key, "needs a history for x and/or y");
    }
  }
  if (m.has("velocity_field")) {
    for (const auto& k : c.component)
      if (k.kind != Prescribed::Free) m.fail("velocity_field", "cannot be combined with fixed, velocity or displacement");
    const YamlMap f = m.child("velocity_field");
    const auto rows = pairs(f, "gradient", 2);
    if (rows.size() != 2) f.fail("gradient", "expected a 2 x 2 matrix [[a, b], [c, d]] (1/s)");
    AffineVelocity a;
    a.gradient << rows[0][0], rows[0][1], rows[1][0], rows[1][1];
    if (f.has("origin")) a.origin = vec2(f, "origin");
    if (f.has("scale")) a.scale = readTimeFunction(f.child("scale"));
    c.field = a;
  }
  return c;
}

Load readLoad(const YamlMap& m) {
  Load l;
  l.name = m.get<std::string>("name");
  l.box = readBox(m.child("box"));
  l.target = m.getEnumOr("on", std::array{LoadTarget::Particles, LoadTarget::Nodes}, l.target);
  l.force = vec2(m, "force");
  if (m.has("history")) l.history = readTimeFunction(m.child("history"));
  return l;
}

CheckpointSettings readCheckpoint(const YamlMap& m) {
  CheckpointSettings c;
  c.everySteps = m.getOr<int>("every_steps", 0, Range::closed(1.0, 2147483647.0));  // 0 only by leaving it out
  c.everyMinutes = m.getOr<double>("every_minutes", 0.0, Range::positive());
  if (!m.has("every_steps") && !m.has("every_minutes")) {
    m.finish();  // an unknown key says more than "nothing given"
    m.failHere("needs every_steps: N and/or every_minutes: M");
  }
  return c;
}

// stop_when: {condition: NAME, load_below: FRACTION, after_time: T} or {gauge: NAME, reaches: MM}.
StopWhen readStopWhen(const YamlMap& m) {
  StopWhen w;
  if (m.has("gauge") == m.has("condition")) m.failHere("stop_when needs exactly one of condition: NAME and gauge: NAME");
  if (m.has("gauge")) {
    w.gauge = m.get<std::string>("gauge");
    w.gaugeReaches = m.get<double>("reaches");
  } else {
    w.condition = m.get<std::string>("condition");
    w.loadBelow = m.get<double>("load_below");
  }
  w.afterTime = m.getOr<double>("after_time", w.afterTime);
  m.finish();
  return w;
}

// gauges: [{name: NAME, at: [x, y], to: [x, y], component: x | y}] (to: optional).
Gauge readGauge(const YamlMap& m) {
  Gauge g;
  g.name = m.get<std::string>("name");
  g.at = vec2(m, "at");
  if (m.has("to")) g.to = vec2(m, "to");
  g.component = m.getEnum("component", {"x", "y"}) == "x" ? 0 : 1;
  m.finish();
  return g;
}

// One degree of freedom of a platen: `held`, `free`, {displacement: HISTORY} or {force: HISTORY}.
PlatenDof readPlatenDof(const YamlMap& m, const std::string& key) {
  PlatenDof d;
  if (!m.has(key)) m.fail(key, "missing: give held, free, {displacement: HISTORY} or {force: HISTORY}");
  if (m.node()[key].IsScalar()) {
    d.drive = m.getEnum(key, {"held", "free"}) == "held" ? PlatenDrive::Held : PlatenDrive::Free;
    return d;
  }
  const YamlMap v = m.child(key);
  if (v.has("displacement") == v.has("force")) {
    v.finish();  // an unknown key says more than "nothing given"
    m.fail(key, "expected held, free, {displacement: HISTORY} or {force: HISTORY}");
  }
  d.drive = v.has("displacement") ? PlatenDrive::Displacement : PlatenDrive::Force;
  d.history = readTimeFunction(v.child(v.has("displacement") ? "displacement" : "force"));
  if (d.drive == PlatenDrive::Force) v.reject("free_until", "applies to a displacement only");
  d.freeUntil = v.getOr<double>("free_until", 0.0);
  return d;
}

// platens: [{name: NAME, boxes: [{min, max}, ...], reference: [x, y], x: DOF, y: DOF, rotation: DOF}]
// (mpm/scene/platen.hpp; reference optional).
Platen readPlaten(const YamlMap& m) {
  Platen p;
  p.name = m.get<std::string>("name");
  for (const YamlMap& b : m.sequence("boxes")) p.boxes.push_back(readBox(b));
  if (p.boxes.empty()) m.fail("boxes", "needs at least one box {min: [x, y], max: [x, y]}");
  if (m.has("reference")) p.reference = vec2(m, "reference");
  p.dof[kPlatenX] = readPlatenDof(m, "x");
  p.dof[kPlatenY] = readPlatenDof(m, "y");
  p.dof[kPlatenRotation] = readPlatenDof(m, "rotation");
  m.finish();
  return p;
}

}  // namespace

Scene readScene(const YamlMap& m) {
  Scene s;
  s.name = m.getOr<std::string>("name", std::filesystem::path(m.file()).stem().string());
  s.grid = readGrid(m.child("grid"));
  s.thickness = m.getOr<double>("thickness", s.thickness);
  // A preset (mpm/scene/presets.hpp) owns its knobs: the scene may not set them too.
  const std::string preset = m.has("preset") ? m.get<std::string>("preset") : "";
  if (!preset.empty() && !findPreset(preset)) m.fail("preset", "unknown preset '" + preset + "' (allowed: " + presetNames() + ")");
  if (!preset.empty()) m.reject("particles_per_cell", presetOwns(preset));
  s.particlesPerCell = m.getOr<int>("particles_per_cell", s.particlesPerCell);

  std::map<std::string, int> names;
  const std::vector<YamlMap> materialMaps = m.sequence("materials");
  for (const YamlMap& mm : materialMaps) {
    MaterialParams p = io::readMaterial(mm);  // checked there by MaterialParams::validate, at its lines
    names.emplace(p.name, static_cast<int>(s.materials.size()));  // (a name defined twice: Scene::validate)
    s.materials.push_back(std::move(p));
  }
  const std::vector<YamlMap> bodyMaps = m.sequence("bodies");
  for (std::size_t i = 0; i < bodyMaps.size(); ++i) {
    const YamlMap& b = bodyMaps[i];
    std::vector<Body> bodies;
    if (b.has("rve")) {
      for (const char* k : {"rectangle", "polygon", "circle", "subtract", "material", "initial_velocity"})
        b.reject(k, "an rve body holds only the rve map");
      bodies = readRveBody(b, names);
    } else {
      bodies.push_back(readBody(b, names));
    }
    for (Body& body : bodies) {
      body.item = static_cast<int>(i);
      s.bodies.push_back(std::move(body));
    }
  }
  if (m.has("solver")) s.solver = readSolver(m.child("solver"), preset);
  if (!preset.empty()) applyPreset(*findPreset(preset), s);
  s.endTime = m.get<double>("end_time");
  s.outputInterval = m.getOr<double>("output_interval", s.outputInterval);
  s.snapshotEvery = m.getOr<int>("snapshot_every", s.snapshotEvery);
  if (m.has("particle_snapshots")) s.particleSnapshots = m.getVector("particle_snapshots", 0);
  if (m.has("checkpoint")) s.checkpoint = readCheckpoint(m.child("checkpoint"));
  if (m.has("conditions"))
    for (const YamlMap& c : m.sequence("conditions")) s.conditions.push_back(readCondition(c));
  if (m.has("loads"))
    for (const YamlMap& l : m.sequence("loads")) s.loads.push_back(readLoad(l));
  if (m.has("platens"))
    for (const YamlMap& p : m.sequence("platens")) s.platens.push_back(readPlaten(p));
  if (m.has("gauges"))
    for (const YamlMap& g : m.sequence("gauges")) s.gauges.push_back(readGauge(g));
  if (m.has("stop_when")) s.stopWhen = readStopWhen(m.child("stop_when"));
  m.finish();
  try {
    s.validate();  // the values, checked in one place (Scene::validate), reported at their lines
    checkMemory(s);  // and whether the machine can hold the run, before anything is allocated
  } catch (const io::ValueError& e) {
    m.failAt(e.key, e.reason);
  }
  return s;
}

Scene loadSceneFile(const std::filesystem::path& path) { return readScene(io::loadYamlFile(path)); }

RveParams readRveParams(const YamlMap& m) {
  RveParams p;
  p.side = m.get<double>("side", Range::positive());
  if (m.has("origin")) p.origin = vec2(m, "origin");
  p.seed = static_cast<std::uint64_t>(m.get<int>("seed", Range::closed(0.0, 2147483647.0)));
  p.volumeFraction = m.get<double>("volume_fraction", Range::open(0.0, 1.0));
  if (m.has("diameters") == m.has("grading"))
    m.failHere("an rve needs exactly one of diameters: [d_min, d_max] and grading: [[d, passing], ...]");
  if (m.has("diameters")) {
    const auto d = m.getVector("diameters", 2, Range::positive());
    if (!(d[1] >= d[0])) m.fail("diameters", "expected [d_min, d_max] with d_max >= d_min (mm)");
    const double q = m.getOr<double>("fuller_exponent", 0.5, Range::open(0.0, 10.0));
    p.grading = fullerGrading(d[0], d[1], q);
  } else {
    m.reject("fuller_exponent", "applies to diameters: [d_min, d_max] only");
    p.grading.clear();
    for (const Vec2& g : pairs(m, "grading", 2)) p.grading.push_back({g[0], g[1]});
  }
  p.itzThickness = m.get<double>("itz_thickness", Range::positive());
  if (m.has("gap")) p.gap = m.get<double>("gap", Range::nonNegative());
  p.attempts = m.getOr<int>("attempts", p.attempts, Range::closed(1.0, 1e9));
  p.tolerance = m.getOr<double>("tolerance", p.tolerance, Range{0.0, 1.0, true, false});
  try {
    p.validate();
  } catch (const std::invalid_argument& e) {
    m.failHere(e.what());
  }
  return p;
}

std::vector<RveParams> sceneRveParams(const YamlMap& scene) {
  std::vector<RveParams> out;
  if (!scene.has("bodies")) return out;
  for (const YamlMap& b : scene.sequence("bodies"))
    if (b.has("rve")) out.push_back(readRveParams(b.child("rve")));
  return out;
}

}  // namespace ecm::mpm
