// Fuzz harness: the material update with arbitrary (in-range) parameters and strain paths.
// Bytes become parameters (mapped into their allowed ranges) and up to 64 strain increments.
// Contract checked: a failed update leaves the state unchanged; a converged one has finite
// stress and tangent, non-negative dissipation and non-decreasing damage.
#include <cmath>
#include <cstdio>
#include <cstdint>
#include <cstdlib>
#include <cstring>

#include "material/material.hpp"

namespace {

struct Bytes {
  const std::uint8_t* data;
  std::size_t size, pos = 0;
  double unit() {  // in [0, 1]
    std::uint16_t v = 0;
    for (int i = 0; i < 2; ++i) v = static_cast<std::uint16_t>(v << 8 | (pos < size ? data[pos++] : 0));
    return v / 65535.0;
  }
  double logRange(double lo, double hi) { return lo * std::pow(hi / lo, unit()); }
  bool more() const { return pos < size; }
};

void require(bool ok, const char* what, const ecm::MaterialParams& p, double bigH, int step, const ecm::UpdateResult& r,
             const ecm::Voigt& strain) {
  if (ok) return;
  std::fprintf(stderr,
               "contract broken: %s at step %d (model %s, E %g, nu %g, ft %g, Ep %g, n %g, h %g, H %g; status %s, "
               "dissipation %g, stress %g %g %g, total strain %.17g %.17g %.17g; tangent %g %g %g / %g %g %g / %g %g %g)\n",
               what, step, ecm::toString(p.model), p.elastic.youngsModulus, p.elastic.poissonRatio, p.tensileStrength,
               p.softeningModulus, p.softeningExponent, p.bandWidth, bigH, ecm::toString(r.status), r.dissipation,
               r.stress[0], r.stress[1], r.stress[2], strain[0], strain[1], strain[2], r.tangent(0, 0), r.tangent(0, 1),
               r.tangent(0, 2), r.tangent(1, 0), r.tangent(1, 1), r.tangent(1, 2), r.tangent(2, 0), r.tangent(2, 1),
               r.tangent(2, 2));
  std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  Bytes b{data, size};
  ecm::MaterialParams p;
  p.model = b.unit() < 0.5 ? ecm::ModelKind::Enriched : ecm::ModelKind::SmearedCrack;
  p.elastic = {b.logRange(1.0, 1e6), -0.99 + 1.48 * b.unit(), b.unit() < 0.5 ? ecm::Hypothesis::PlaneStress : ecm::Hypothesis::PlaneStrain};
  p.tensileStrength = b.logRange(1e-3, 1e3);
  p.softeningModulus = b.logRange(1e-3, 1e6);
  p.softeningExponent = 0.001 + 0.498 * b.unit();
  p.bandWidth = b.logRange(1e-4, 10.0);
  // The second band (enriched only) needs room for two bands: H >= 2 h (1 + 1e-6).
  const bool twoBands = p.model == ecm::ModelKind::Enriched && b.unit() < 0.5;
  if (twoBands) p.secondBand = ecm::SecondBandOption::Orthogonal;
  const double bigH = (twoBands ? 2.0 : 1.0) * p.bandWidth * (1.0 + b.logRange(1e-6, 1e6));
  const ecm::Material m(p);
  const auto size_ = ecm::EffectiveSize::fixed(bigH);
  ecm::MaterialPoint point;
  const double scale = p.tensileStrength / p.elastic.youngsModulus;
  for (int i = 0; i < 64 && b.more(); ++i) {
    const ecm::Voigt d = scale * b.logRange(1e-4, 1e4) * ecm::Voigt(2 * b.unit() - 1, 2 * b.unit() - 1, 2 * b.unit() - 1);
    const ecm::MaterialPoint before = point;
    const ecm::UpdateResult r = m.update(point, d, size_, ecm::SnapBackPolicy::Stop);
    if (!r.converged()) {
      require(point.strain == before.strain && point.integrity == before.integrity &&
                  point.band.has_value() == before.band.has_value() &&
                  point.secondBand.has_value() == before.secondBand.has_value(),
              "failed update changed the state", p, bigH, i, r, point.strain);
      continue;
    }
    require(r.stress.allFinite() && r.tangent.allFinite() && std::isfinite(r.dissipation), "non-finite result", p, bigH,
            i, r, point.strain);
    require(r.dissipation >= 0.0, "negative dissipation", p, bigH, i, r, point.strain);
    require(point.damage() >= before.damage() && point.damage() <= 1.0, "damage decreased", p, bigH, i, r, point.strain);
    require(!before.secondBand || (point.secondBand && point.secondBand->damage() >= before.secondBand->damage() &&
                                   point.secondBand->damage() <= 1.0),
            "second band's damage decreased", p, bigH, i, r, point.strain);
  }
  return 0;
}
