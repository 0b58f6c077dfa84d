#include "umat/umat_props.hpp"

#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "umat/umat_layout.hpp"

namespace ecm::umat {

namespace {

// A constant as a deck reads it: the shortest text that reads back as the same double, if it
// fits in the 20 characters a field of CalculiX holds (else as many digits as fit), with a
// decimal point.
std::string deckNumber(double v) {
  char text[40];
  const auto [end, error] = std::to_chars(text, text + sizeof text, v);
  std::string s(text, error == std::errc() ? end : text);
  if (s.empty() || s.size() > 20) {
    for (int digits = 17; digits > 1; --digits)
      if (std::snprintf(text, sizeof text, "%.*g", digits, v) <= 20) break;
    s = text;
  }
  if (s.find_first_of(".eEn") == std::string::npos) s += '.';
  return s;
}

// "2.5" -> "2p5": a size in a material's name (decks read '.' as part of a number elsewhere).
std::string sizeTag(double h) {
  std::string s = deckNumber(h);
  if (!s.empty() && s.back() == '.') s.pop_back();
  for (char& c : s)
    if (c == '.') c = 'p';
  return s;
}

bool plainName(const std::string& name) {
  if (name.empty()) return false;
  for (const char c : name)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_' && c != '-') return false;
  return true;
}

std::string upper(std::string s) {
  for (char& c : s) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return s;
}

}  // namespace

std::vector<double> propsFor(const MaterialParams& m, double effectiveSize, SnapBackPolicy snapBack,
                             std::optional<int> substepLevels) {
  if (m.model == ModelKind::SmearedCrack)
    throw ParameterError("ecm's UMAT carries the enriched and the linear elastic models, not the smeared crack", "model");
  if (m.model == ModelKind::Enriched && m.secondBand != SecondBandOption::Off)
    throw ParameterError("ecm's UMAT carries one band: second_band must be off", "second_band");
  m.validate();
  const bool enriched = m.model == ModelKind::Enriched;
  if (enriched && effectiveSize > 0.0)
    if (const std::string why = effectiveSizeProblem(effectiveSize, m.bandWidth); !why.empty())
      throw ParameterError("H = " + numberText(effectiveSize, 6) + " mm: " + why, "effective_size");
  if (!(effectiveSize >= 0.0) || !std::isfinite(effectiveSize))
    throw ParameterError("H = " + numberText(effectiveSize, 6) + " mm: must be > 0, or 0 for the caller's CELENT", "effective_size");
  std::vector<double> p(kMinProps, 0.0);
  p[kModel] = enriched ? 1.0 : 0.0;
  p[kYoungsModulus] = m.elastic.youngsModulus;
  p[kPoissonRatio] = m.elastic.poissonRatio;
  if (enriched) {
    p[kTensileStrength] = m.tensileStrength;
    p[kSofteningModulus] = m.softeningModulus;
    p[kSofteningExponent] = m.softeningExponent;
    p[kBandWidth] = m.bandWidth;
    p[kEffectiveSize] = effectiveSize;
  }
  p[kSnapBack] = snapBack == SnapBackPolicy::Release ? 1.0 : 0.0;
  if (substepLevels) p.push_back(static_cast<double>(*substepLevels));
  return p;
}

std::string materialCard(const MaterialParams& m, const CardRequest& request) {
  if (!plainName(request.name))
    throw ParameterError("material name '" + request.name + "': letters, digits, '_' and '-' only", "name");
  if (request.effectiveSizes.empty()) throw ParameterError("no element size: give H (mm) for at least one", "element_size");
  const bool calculix = request.dialect == Dialect::CalculiX;
  std::ostringstream out;
  out << "** ecm's UMAT (libecm_umat.so, docs/fe-codes.md): material '" << m.name << "'";
  if (!request.source.empty()) out << ", " << request.source;
  out << ". Units: mm, N, MPa, tonne.\n";
  out << "** PROPS: model (1 enriched), E (MPa), nu, f_t' (MPa), E_p (MPa), n, h (mm), H (mm"
      << (calculix ? "" : "; 0 = CELENT") << "), snap_back (1 release, 0 stop)\n";
  for (const double size : request.effectiveSizes) {
    if (calculix && !(size > 0.0))
      throw ParameterError("H = 0 (CELENT) for CalculiX, which passes no CELENT: give the element size", "element_size");
    const std::vector<double> props = propsFor(m, size, request.snapBack);
    std::string name = upper(request.name);
    if (request.effectiveSizes.size() > 1) name += "_H" + sizeTag(size);
    if (calculix && name.rfind("ABAQUS", 0) != 0) name = "ABAQUS_" + name;  // CalculiX calls a UMAT for these only
    if (name.size() > 80) throw ParameterError("material name '" + name + "' is longer than 80 characters", "name");
    out << "*MATERIAL, NAME=" << name << "\n";
    out << "*USER MATERIAL, CONSTANTS=" << props.size() << "\n";
    for (std::size_t i = 0; i < props.size(); ++i)  // eight constants a line
      out << deckNumber(props[i]) << (i + 1 == props.size() || i % 8 == 7 ? "\n" : ", ");
    out << "*DEPVAR\n" << kStateCount << "\n";
    if (m.density > 0.0) out << "*DENSITY\n" << deckNumber(m.density) << "\n";
  }
  return out.str();
}

}  // namespace ecm::umat
