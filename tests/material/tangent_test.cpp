// Consistent tangents against central finite differences (MTest's
// CompareToNumericalTangentOperator): relative error <= 1e-6 in every regime of a point: elastic
// loading, softening, unloading, reloading inside the envelope, and a cracked point under shear.
#include <gtest/gtest.h>

#include <functional>

#include "material/material.hpp"
#include "../paper_constants.hpp"

namespace ecm {
namespace {

// Runs `increment` from a copy of the committed point; returns the stress and tangent.
using Probe = std::function<UpdateResult(const Voigt& increment)>;

double tangentError(const Probe& probe, const Voigt& increment, double delta) {
  const UpdateResult r = probe(increment);
  EXPECT_TRUE(r.converged());
  Tangent fd;
  for (int j = 0; j < 3; ++j) {
    Voigt e = Voigt::Zero();
    e[j] = delta;
    const UpdateResult plus = probe(increment + e), minus = probe(increment - e);
    EXPECT_TRUE(plus.converged() && minus.converged());
    fd.col(j) = (plus.stress - minus.stress) / (2.0 * delta);
  }
  return (r.tangent - fd).cwiseAbs().maxCoeff() / r.tangent.cwiseAbs().maxCoeff();
}

struct Point {
  Material material;
  MaterialPoint point;
  EffectiveSize size = EffectiveSize::fixed(2.5);
  explicit Point(const MaterialParams& p) : material(p) {}
  void load(const Voigt& increment, int steps) {
    for (int i = 0; i < steps; ++i) ASSERT_TRUE(material.update(point, increment / steps, size, SnapBackPolicy::Stop).converged());
  }
  Probe probe() const {
    return [this](const Voigt& d) {
      MaterialPoint copy = point;
      return material.update(copy, d, size, SnapBackPolicy::Stop);
    };
  }
};

MaterialParams params(ModelKind kind, Hypothesis hyp = Hypothesis::PlaneStress) {
  MaterialParams p{.name = "tangent",
                   .model = kind, .elastic = {test::kE, test::kNu, hyp}, .tensileStrength = test::kFt,
                   .softeningModulus = test::kEp, .softeningExponent = test::kN, .bandWidth = test::kBandWidth};
  return p;
}

constexpr double kTol = 1e-6;
constexpr double kDelta = 1e-9;  // strain perturbation; increments below are >= 1e-6

class TangentTest : public ::testing::TestWithParam<std::tuple<ModelKind, Hypothesis>> {};

TEST_P(TangentTest, MatchesFiniteDifferencesInEveryRegime) {
  const auto [kind, hyp] = GetParam();
  Point p(params(kind, hyp));
  const Voigt tension(1.0, 0.1, 0.2);  // principal axes off the grid axes
  // elastic loading
  EXPECT_LT(tangentError(p.probe(), 5e-5 * tension, kDelta), kTol) << "elastic loading";
  if (kind == ModelKind::LinearElastic) return;
  // softening (well past onset)
  p.load(1.2e-4 * tension, 20);
  EXPECT_LT(tangentError(p.probe(), 2e-6 * tension, kDelta), kTol) << "softening";
  // unloading (secant)
  p.load(1e-5 * tension, 5);
  EXPECT_LT(tangentError(p.probe(), -2e-5 * tension, kDelta), kTol) << "unloading";
  // reloading, still inside the envelope
  p.load(-4e-5 * tension, 5);
  EXPECT_LT(tangentError(p.probe(), 2e-5 * tension, kDelta), kTol) << "reloading";
  // a cracked point under shear (mixed mode), damage growing
  p.load(3e-5 * tension, 5);
  p.load(Voigt(0.0, 0.0, 2e-5), 5);
  EXPECT_LT(tangentError(p.probe(), Voigt(0.0, 0.0, 3e-6), kDelta), kTol) << "shear";
}

// The secant tangent (Eq. (10) with the band's damage frozen), which the implicit MPM gives to
// points that make Newton cycle: with the damage frozen the point is linear, so it is the exact
// response to any unloading increment (not only the derivative at it), the tangent an unloading
// update returns, and stiffer than the consistent tangent of the softening point it is taken at.
TEST(SecantTangent, IsTheExactResponseToUnloadingAndStifferThanSoftening) {
  Point p(params(ModelKind::Enriched));
  const Voigt tension(1.0, 0.1, 0.2);
  p.load(1.2e-4 * tension, 20);  // softening, well past onset
  ASSERT_TRUE(p.point.band);
  const TwoPhasePoint& model = *p.material.enriched();
  const Tangent secant = model.secantTangent(*p.point.band);
  const Voigt before = p.material.stress(p.point);
  const UpdateResult softening = p.probe()(2e-6 * tension);
  for (const double size : {1e-6, 1e-5, 4e-5}) {  // a finite unloading increment: linear response
    const Voigt d = -size * tension;
    const UpdateResult r = p.probe()(d);
    ASSERT_TRUE(r.converged());
    EXPECT_EQ(r.dissipation, 0.0) << size;
    EXPECT_LT((r.stress - before - secant * d).norm(), 1e-9 * test::kFt) << size;
    EXPECT_LT((r.tangent - secant).cwiseAbs().maxCoeff(), 1e-9 * test::kE) << size;
  }
  // Along the crack normal the secant carries the band's traction at its damage, the softening
  // tangent less (negative on the descending branch).
  const Vec2 n = p.point.band->crackNormal;
  const Voigt nn(n[0] * n[0], n[1] * n[1], 2.0 * n[0] * n[1]);
  EXPECT_GT(nn.dot(secant * nn), 0.0);
  EXPECT_GT(nn.dot(secant * nn), nn.dot(softening.tangent * nn));
}

INSTANTIATE_TEST_SUITE_P(AllModels, TangentTest,
                         ::testing::Combine(::testing::Values(ModelKind::LinearElastic, ModelKind::SmearedCrack,
                                                              ModelKind::Enriched),
                                            ::testing::Values(Hypothesis::PlaneStress, Hypothesis::PlaneStrain)),
                         [](const auto& info) {
                           return std::string(toString(std::get<0>(info.param))) +
                                  (std::get<1>(info.param) == Hypothesis::PlaneStress ? "_plane_stress" : "_plane_strain");
                         });

}  // namespace
}  // namespace ecm
