#include "calibration/calibration_input.hpp"

#include <cmath>
#include <limits>
#include <sstream>

#include "calibration/calibration_error.hpp"
#include "calibration/fracture_energy.hpp"
#include "calibration/target_csv.hpp"
#include "material/parameter_check.hpp"

namespace ecm::calibration {

const char* toString(CalibrationMode m) {
  switch (m) {
    case CalibrationMode::Forward: return "forward";
    case CalibrationMode::SolveSofteningModulus: return "solve_softening_modulus";
    case CalibrationMode::Fit: return "fit";
    case CalibrationMode::CrackBand: return "crack_band";
  }
  return "?";
}

const std::vector<Quantity>& quantities() {
  constexpr double inf = std::numeric_limits<double>::infinity();
  static const std::vector<Quantity> q = {
      {"youngs_modulus", "--E", "E", "MPa", &CalibrationInput::youngsModulus, io::Range::positive(), ""},
      {"poisson_ratio", "--nu", "nu", "-", &CalibrationInput::poissonRatio, io::Range::open(-1.0, 0.5), ""},
      {"tensile_strength", "--ft", "ft", "MPa", &CalibrationInput::tensileStrength, io::Range::positive(), ""},
      {"fracture_energy", "--GF", "GF", "N/mm", &CalibrationInput::fractureEnergy, io::Range::positive(), ""},
      {"band_width", "--h", "h", "mm", &CalibrationInput::bandWidth, io::Range::positive(), ""},
      {"softening_exponent", "--n", "n", "-", &CalibrationInput::softeningExponent, io::Range::open(0.0, 0.5),
       "n >= 0.5 gives an infinite fracture energy (F ~ D^-2n near failure), n <= 0 no softening of Eq. (13) form"},
      {"softening_modulus", "--Ep", "Ep", "MPa", &CalibrationInput::softeningModulus, io::Range::positive(), ""},
      {"smeared_element_size", "--smeared-H", "H", "mm", &CalibrationInput::smearedSize, io::Range::positive(), ""},
      {"density", "--density", "rho", "t/mm^3", &CalibrationInput::density, io::Range{0.0, inf, true, false}, ""},
  };
  return q;
}

CalibrationInput readCalibrationInput(const std::filesystem::path& path) { return readCalibrationInput(io::loadYamlFile(path)); }

CalibrationInput readCalibrationInput(const io::YamlMap& m) {
  CalibrationInput in;
  for (const Quantity& q : quantities()) {
    if (!m.has(q.key)) continue;
    in.*q.member = m.get<double>(q.key);  // type and finiteness here; range in planCalibration
    in.origin[q.key] = {m.file(), m.line(q.key)};
  }
  if (m.has("fit")) {
    in.fit = m.getEnum("fit", {"hordijk"});
    in.origin["fit"] = {m.file(), m.line("fit")};
  }
  if (m.has("fit_csv")) {
    in.fitCsv = m.directory() / m.get<std::string>("fit_csv");
    in.origin["fit_csv"] = {m.file(), m.line("fit_csv")};
  }
  if (m.has("out")) in.out = m.get<std::string>("out");
  if (m.has("write_material")) in.writeMaterial = m.get<std::string>("write_material");
  if (m.has("write_umat")) in.writeUmat = m.get<std::string>("write_umat");
  if (m.has("element_sizes")) {
    in.elementSizes = m.scalarSequence<double>("element_sizes");
    in.origin["element_sizes"] = {m.file(), m.line("element_sizes")};
  }
  if (m.has("umat_dialect")) {
    in.umatDialect = m.getEnum("umat_dialect", {"calculix", "abaqus"});
    in.origin["umat_dialect"] = {m.file(), m.line("umat_dialect")};
  }
  if (m.has("name")) in.name = m.get<std::string>("name");
  if (m.has("hypothesis")) {
    in.hypothesis = m.getEnum("hypothesis", {"plane_stress", "plane_strain"});
    in.origin["hypothesis"] = {m.file(), m.line("hypothesis")};
  }
  m.finish();
  return in;
}

void overlay(CalibrationInput& base, const CalibrationInput& top) {
  for (const Quantity& q : quantities()) {
    if (!(top.*q.member)) continue;
    base.*q.member = top.*q.member;
    base.origin.erase(q.key);
  }
  const auto take = [&](auto& dst, const auto& src, const char* key) {
    if (!src) return;
    dst = src;
    base.origin.erase(key);
  };
  take(base.fit, top.fit, "fit");
  take(base.fitCsv, top.fitCsv, "fit_csv");
  take(base.fitPoints, top.fitPoints, "fit_points");
  take(base.out, top.out, "out");
  take(base.writeMaterial, top.writeMaterial, "write_material");
  take(base.writeUmat, top.writeUmat, "write_umat");
  take(base.elementSizes, top.elementSizes, "element_sizes");
  take(base.umatDialect, top.umatDialect, "umat_dialect");
  take(base.name, top.name, "name");
  take(base.hypothesis, top.hypothesis, "hypothesis");
}

namespace {

const Quantity& quantity(const char* key) {
  for (const Quantity& q : quantities())
    if (std::string(q.key) == key) return q;
  throw std::logic_error(std::string("no quantity ") + key);
}

std::string label(const Quantity& q) { return std::string(q.key) + " " + q.symbol + " (" + q.flag + ")"; }

// "3 MPa", or just "0.5" for dimensionless quantities.
std::string withUnit(double v, const Quantity& q) {
  return std::string(q.unit) == "-" ? numberText(v, 10) : numberText(v, 10) + " " + q.unit;
}

class Checker {
 public:
  explicit Checker(const CalibrationInput& in) : in_(in) {}

  [[noreturn]] void fail(const std::string& key, const std::string& reason) const {
    if (const auto it = in_.origin.find(key); it != in_.origin.end())
      throw io::InputError(it->second.first, it->second.second, reason);
    throw CalibrationError(reason);
  }

  // "key 'softening_exponent' (n)" for a YAML value, "softening_exponent n (--n)" otherwise.
  std::string label(const char* key) const {
    const Quantity& q = quantity(key);
    if (in_.origin.count(key)) return std::string("key '") + q.key + "' (" + q.symbol + ")";
    return calibration::label(q);
  }

  bool given(const char* key) const { return (in_.*quantity(key).member).has_value(); }

  double value(const char* key, const std::string& purpose) const {
    const Quantity& q = quantity(key);
    const std::optional<double>& v = in_.*q.member;
    if (!v) throw CalibrationError("missing " + label(key) + ", needed " + purpose);
    if (!std::isfinite(*v)) fail(key, label(key) + " = " + numberText(*v, 10) + " is not a finite number");
    if (!q.range.contains(*v))
      fail(key, label(key) + " = " + withUnit(*v, q) + " is outside the allowed range " + q.range.str() +
                    (*q.rangeNote ? std::string(": ") + q.rangeNote : std::string()));
    return *v;
  }

  void forbid(const char* key, const std::string& why) const {
    if (given(key)) fail(key, label(key) + " " + why);
  }

 private:
  const CalibrationInput& in_;
};

// The UMAT card's element sizes and dialect: sizes above the band width, and given for CalculiX
// (which passes no CELENT); Abaqus without sizes gets H = 0 (its CELENT per element).
void planUmatCard(const Checker& c, const CalibrationInput& in, CalibrationPlan& p) {
  if (p.mode == CalibrationMode::CrackBand)
    c.fail("write_umat", "--write-umat writes ecm's enriched point: the crack band (--smeared-H) has no UMAT card");
  if (in.umatDialect && *in.umatDialect == "abaqus") p.dialect = umat::Dialect::Abaqus;
  else if (in.umatDialect && *in.umatDialect != "calculix")
    c.fail("umat_dialect", "umat_dialect '" + *in.umatDialect + "' is not one of: calculix, abaqus");
  if (in.elementSizes) p.elementSizes = *in.elementSizes;
  if (p.elementSizes.empty()) {
    if (p.dialect == umat::Dialect::CalculiX)
      c.fail("element_sizes", "--write-umat for CalculiX needs the element sizes H (mm): --element-size 2.5[,5,...] "
                              "(CalculiX passes no CELENT; --umat-dialect abaqus takes H from CELENT)");
    p.elementSizes = {0.0};
    return;
  }
  for (const double size : p.elementSizes) {
    if (!(size > 0.0) || !std::isfinite(size))
      c.fail("element_sizes", "element size H = " + numberText(size, 10) + " mm: must be a positive number");
    if (const std::string why = effectiveSizeProblem(size, p.width); !why.empty())
      c.fail("element_sizes", "element size H = " + numberText(size, 10) + " mm: " + why);
  }
}

}  // namespace

CalibrationPlan planCalibration(const CalibrationInput& in) {
  const Checker c(in);
  CalibrationPlan p;
  const bool fitting = in.fit || in.fitCsv || in.fitPoints;
  if ((in.fit ? 1 : 0) + (in.fitCsv ? 1 : 0) + (in.fitPoints ? 1 : 0) > 1)
    throw CalibrationError("give either --fit hordijk or --fit-csv FILE, not both");
  if (c.given("smeared_element_size")) {
    p.mode = CalibrationMode::CrackBand;
  } else if (fitting) {
    p.mode = CalibrationMode::Fit;
  } else if (c.given("fracture_energy")) {
    p.mode = CalibrationMode::SolveSofteningModulus;
  } else if (c.given("softening_modulus")) {
    p.mode = CalibrationMode::Forward;
  } else {
    throw CalibrationError(
        "nothing to calibrate: give --GF and --n (solve E_p), --GF with --fit hordijk or --fit-csv FILE (fit n and "
        "E_p), --Ep and --n without --GF (forward: G_F), or --GF, --n and --smeared-H (crack band)");
  }

  std::string purpose;
  switch (p.mode) {
    case CalibrationMode::Forward: purpose = "for the forward computation of G_F"; break;
    case CalibrationMode::SolveSofteningModulus: purpose = "to solve E_p from G_F"; break;
    case CalibrationMode::Fit: purpose = "to fit n and E_p"; break;
    case CalibrationMode::CrackBand: purpose = "for the crack-band calibration"; break;
  }
  p.law.youngsModulus = c.value("youngs_modulus", purpose);
  p.law.tensileStrength = c.value("tensile_strength", purpose);
  if (p.mode == CalibrationMode::CrackBand) {
    if (fitting) throw CalibrationError("the crack-band calibration (--smeared-H) takes n as given; it cannot be combined with a fit");
    c.forbid("band_width", "is not used by the crack-band calibration (the width is the element size H)");
    c.forbid("softening_modulus", "is the result of the crack-band calibration; it cannot be given");
    p.width = c.value("smeared_element_size", purpose);
  } else {
    p.width = c.value("band_width", purpose);
  }
  if (p.mode == CalibrationMode::Fit) {
    c.forbid("softening_exponent", "is determined by the fit; leave it out (or drop --fit to solve E_p for it)");
    c.forbid("softening_modulus", "is determined by the fit; it cannot be given");
  } else {
    p.law.softeningExponent = c.value("softening_exponent", purpose);
  }
  if (p.mode == CalibrationMode::Forward) {
    p.law.softeningModulus = c.value("softening_modulus", purpose);
  } else {
    if (p.mode == CalibrationMode::SolveSofteningModulus)
      c.forbid("softening_modulus", "cannot be given together with fracture_energy GF: give E_p (forward) or G_F (solve E_p)");
    p.fractureEnergy = c.value("fracture_energy", purpose);
    if (p.mode != CalibrationMode::CrackBand) {
      const double least = minimumFractureEnergy(p.law.youngsModulus, p.law.tensileStrength, p.width);
      if (!(p.fractureEnergy > least))
        c.fail("fracture_energy", c.label("fracture_energy") + " = " + numberText(p.fractureEnergy, 10) +
                                      " N/mm is below the elastic minimum h ft^2/(2E) = " + numberText(least, 10) +
                                      " N/mm: no softening law of the form of Eq. (13) dissipates so little");
    }
  }
  if (in.fit) {
    p.target = hordijkCurve(p.law.tensileStrength, p.fractureEnergy);
  } else if (in.fitCsv) {
    p.target = readTargetCsv(*in.fitCsv);
  } else if (in.fitPoints) {
    validateTarget(*in.fitPoints);
    p.target = in.fitPoints;
  }

  if (in.out) p.out = *in.out;
  p.writeMaterial = in.writeMaterial;
  if (in.name) p.name = *in.name;
  if (in.hypothesis) {
    if (*in.hypothesis == "plane_strain") {
      p.hypothesis = Hypothesis::PlaneStrain;
    } else if (*in.hypothesis != "plane_stress") {
      c.fail("hypothesis", "hypothesis '" + *in.hypothesis + "' is not one of: plane_stress, plane_strain");
    }
  }
  p.writeUmat = in.writeUmat;
  if (p.writeUmat) planUmatCard(c, in, p);
  if (p.writeMaterial || p.writeUmat) {
    const std::string purpose = p.writeMaterial ? "for --write-material" : "for --write-umat";
    p.poissonRatio = c.value("poisson_ratio", purpose);
    if (c.given("density")) p.density = c.value("density", purpose);
  } else {
    if (c.given("poisson_ratio")) p.poissonRatio = c.value("poisson_ratio", "");
    if (c.given("density")) p.density = c.value("density", "");
  }
  return p;
}

}  // namespace ecm::calibration
