#include "cohesive/scene.hpp"

#include <cmath>
#include <filesystem>

#include "cohesive/table_file.hpp"
#include "io/yaml_input.hpp"
#include "material/parameter_check.hpp"

namespace ecm::cohesive {

namespace {

using io::Range;
using io::YamlMap;

// table: {file: PATH, initial_stiffness: K0}, PATH relative to the scene's folder. The rows'
// faults are the CSV's (FILE:LINE); K0's is the scene's. The table's area is not checked against
// material.fracture_energy: it stops at a finite opening (ecm-cohesive reports the area).
void readTableLaw(const YamlMap& top, double tensileStrength, TableInterface& table) {
  const YamlMap t = top.child("table");
  const std::filesystem::path file = t.directory() / t.get<std::string>("file");
  const double k0 = t.get<double>("initial_stiffness", Range::positive());
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec)) t.fail("file", "no table file '" + file.string() + "'");
  table = readTableFile(file);
  table.initialStiffness = k0;
  // The first row is f_t': a table of another concrete than the scene's is a mistake.
  if (std::abs(table.tensileStrength() / tensileStrength - 1.0) > 1e-6)
    t.fail("file", "the table starts at " + std::to_string(table.tensileStrength()) + " MPa, not at material.tensile_strength = " +
                       std::to_string(tensileStrength) + " MPa");
  try {
    table.checkStiffness();
  } catch (const ParameterError& e) {
    t.fail("initial_stiffness", e.what());
  }
}

Scene readScene(const YamlMap& top, const SceneOverrides& o) {
  Scene s;
  s.file = top.file();
  s.name = top.get<std::string>("name");
  const std::string problem = top.getEnum("problem", {"beam", "den_tension", "bar"});
  s.problem = problem == "beam" ? Problem::beam : problem == "den_tension" ? Problem::denTension : Problem::bar;
  s.bulk.thickness = top.get<double>("thickness", Range::positive());
  s.cellSize = top.get<double>("cell", Range::positive());
  if (o.cellSize) {
    if (!(*o.cellSize > 0.0)) throw io::InputError("--cell", 1, "the cell size must be > 0, not " + std::to_string(*o.cellSize));
    s.cellSize = *o.cellSize;
  }

  const YamlMap mat = top.child("material");
  s.bulk.youngsModulus = mat.get<double>("youngs_modulus", Range::positive());
  s.bulk.poissonRatio = mat.get<double>("poisson_ratio", Range{-1.0, 0.5, false, false});
  const double ft = mat.get<double>("tensile_strength", Range::positive());
  s.fractureEnergy = mat.get<double>("fracture_energy", Range::positive());

  const std::string law = top.getEnum("law", {"band", "hordijk", "table"});
  s.law.kind = law == "band" ? LawKind::band : law == "hordijk" ? LawKind::hordijk : LawKind::table;
  if (o.law) s.law.kind = *o.law;
  if (s.law.kind != LawKind::hordijk) top.reject("hordijk", "only with law: hordijk");
  if (s.law.kind != LawKind::table) top.reject("table", "only with law: table");
  else if (!top.has("table")) top.fail("table", "law 'table' needs the block table: {file, initial_stiffness}");
  // The band block serves the band law, and Hordijk's default K0 (E/h); a table law would ignore it.
  if (s.law.kind == LawKind::table) top.reject("band", "only with law: band or hordijk");
  const bool hasBand = top.has("band");
  if (s.law.kind == LawKind::band && !hasBand) top.fail("band", "law 'band' needs the block band: {band_width, softening_modulus, softening_exponent}");
  if (hasBand) {
    const YamlMap b = top.child("band");
    s.law.band.bandWidth = b.get<double>("band_width", Range::positive());
    s.law.band.law = {s.bulk.youngsModulus, ft, b.get<double>("softening_modulus", Range::positive()),
                      b.get<double>("softening_exponent", Range::open(0.0, 0.5))};
    if (s.law.kind == LawKind::band) {
      const double gf = bandFractureEnergy(s.law.band);
      if (std::abs(gf / s.fractureEnergy - 1.0) > 1e-3)
        b.fail("softening_modulus", "the band law dissipates h int F dD = " + std::to_string(gf) + " N/mm, not material.fracture_energy = " +
                                        std::to_string(s.fractureEnergy) + " N/mm (within 0.1 %): calibrate (E_p, n) with ecm-calibrate");
    }
  }
  s.law.hordijk = {ft, s.fractureEnergy, hasBand ? s.bulk.youngsModulus / s.law.band.bandWidth : 1e6};
  if (top.has("hordijk")) {
    const YamlMap h = top.child("hordijk");
    s.law.hordijk.initialStiffness = h.getOr<double>("initial_stiffness", s.law.hordijk.initialStiffness, Range::positive());
  }
  if (s.law.kind == LawKind::hordijk) {
    try {
      s.law.hordijk.validate();
    } catch (const ParameterError& e) {
      top.failAt("hordijk.initial_stiffness", e.what());
    }
  }

  if (s.law.kind == LawKind::table) readTableLaw(top, ft, s.law.table);

  switch (s.problem) {
    case Problem::beam: {
      top.reject("panel", "only for problem: den_tension");
      top.reject("bar", "only for problem: bar");
      const YamlMap g = top.child("beam");
      BeamGeometry& b = s.beam;
      b.depth = g.get<double>("depth", Range::positive());
      b.length = g.get<double>("length", Range::positive());
      b.span = g.get<double>("span", Range{0.0, b.length, false, true});
      b.notchWidth = g.get<double>("notch_width", Range::positive());
      b.notchDepth = g.get<double>("notch_depth", Range{0.0, b.depth, false, false});
      b.cmodGauge = g.get<double>("cmod_gauge", Range{b.notchWidth, b.span, true, false});
      b.supportBox = g.getEnum("supports", {"node", "box"}) == "box";
      b.loadBox = g.getEnum("load", {"node", "box"}) == "box";
      if (b.supportBox || b.loadBox) b.boxWidth = g.get<double>("box_width", Range{0.0, b.notchWidth, false, true});
      else g.reject("box_width", "only with supports: box or load: box");
      break;
    }
    case Problem::denTension: {
      top.reject("beam", "only for problem: beam");
      top.reject("bar", "only for problem: bar");
      const YamlMap g = top.child("panel");
      PanelGeometry& p = s.panel;
      p.width = g.get<double>("width", Range::positive());
      p.height = g.get<double>("height", Range::positive());
      p.notchDepth = g.get<double>("notch_depth", Range{0.0, 0.5 * p.width, false, false});
      p.notchWidth = g.get<double>("notch_width", Range{0.0, p.height, false, false});
      p.topHeldInX = g.getEnum("top_edge_x", {"free", "held"}) == "held";
      break;
    }
    case Problem::bar: {
      top.reject("beam", "only for problem: beam");
      top.reject("panel", "only for problem: den_tension");
      const YamlMap g = top.child("bar");
      s.bar.length = g.get<double>("length", Range::positive());
      s.bar.height = g.get<double>("height", Range::positive());
      break;
    }
  }

  const YamlMap c = top.child("control");
  SolverSettings& v = s.solver;
  v.finalControl = c.get<double>("final", Range::positive());
  v.maxStep = c.get<double>("max_step", Range{0.0, v.finalControl, false, true});
  v.firstStep = c.getOr<double>("first_step", v.maxStep, Range{0.0, v.maxStep, false, true});
  v.minStep = c.getOr<double>("min_step", 1e-6 * v.maxStep, Range{0.0, v.firstStep, false, true});
  v.maxLoadStep = c.getOr<double>("max_load_step", 0.0, Range::nonNegative());
  if (top.has("newton")) {
    const YamlMap nm = top.child("newton");
    v.tolerance = nm.getOr<double>("tolerance", v.tolerance, Range{1e-15, 1e-3, true, true});
    v.maxIterations = nm.getOr<int>("max_iterations", v.maxIterations, Range{1.0, 1000.0, true, true});
  }
  top.finish();
  return s;
}

}  // namespace

Scene readScene(const std::filesystem::path& path, const SceneOverrides& o) { return readScene(io::loadYamlFile(path), o); }
Scene parseScene(const std::string& text, const std::string& name, const SceneOverrides& o) {
  return readScene(io::parseYaml(text, name), o);
}

HalfModel buildModel(const Scene& s) {
  switch (s.problem) {
    case Problem::beam: return beamModel(s.beam, s.bulk, s.cellSize);
    case Problem::denTension: return panelTensionModel(s.panel, s.bulk, s.cellSize);
    case Problem::bar: return barTensionModel(s.bar, s.bulk, s.cellSize);
  }
  return {};
}

}  // namespace ecm::cohesive
