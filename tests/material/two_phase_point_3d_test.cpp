// The enriched point in 3D (material/two_phase_point_3d.hpp, docs/model.md "The point in 3D"):
// objectivity, the 2D hypotheses as special cases of 3D, closed forms, the energy identity, the
// 6 x 6 consistent tangent against finite differences, and random-path physics checks.
#include "material/two_phase_point_3d.hpp"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <random>

#include "material/material.hpp"
#include "material/material_3d.hpp"
#include "material/uniaxial_closed_form.hpp"
#include "../paper_constants.hpp"

namespace ecm {
namespace {

const DamageLawParams kLaw{test::kE, test::kFt, test::kEp, test::kN};

MaterialParams params3(double nu = test::kNu, Hypothesis hyp = Hypothesis::ThreeDimensional) {
  MaterialParams p = test::paperConcreteMaterial();
  p.elastic = {test::kE, nu, hyp};
  return p;
}

// A random rotation (uniform quaternion, fixed seed).
Mat3 randomRotation(std::mt19937_64& rng) {
  std::normal_distribution<double> g;
  return Eigen::Quaterniond(g(rng), g(rng), g(rng), g(rng)).normalized().toRotationMatrix();
}

// Uniaxial strain e along unit d: eps = e d (x) d.
Voigt6 uniaxialStrain(const Vec3& d, double e) {
  Voigt6 s = stressVoigt(e * d * d.transpose());
  s.tail<3>() *= 2.0;
  return s;
}

TEST(TwoPhasePoint3D, TensionThenShearIsObjectiveUnderAnyRotation) {
  // Objectivity: the path rotated by R gives the stress rotated by R, at every increment, with
  // the band normal rotated too (the 3D point has no preferred axes). Tolerance 1e-10 f_t'.
  std::mt19937_64 rng(40);
  const Material3D m(params3());
  const auto size = EffectiveSize3::fixed(2.5);
  std::vector<Voigt6> path;
  for (int i = 0; i < 60; ++i) path.push_back(uniaxialStrain(Vec3::UnitX(), 4e-6));  // tension along x past the peak
  Voigt6 shear = Voigt6::Zero();
  shear[5] = 2e-5, shear[3] = 0.7e-5;
  for (int i = 0; i < 40; ++i) path.push_back(shear);  // then shear (mixed mode, sliding in y and z)
  for (int trial = 0; trial < 5; ++trial) {
    const Mat3 r = trial == 0 ? Mat3::Identity() : randomRotation(rng);
    MaterialPoint3 a, b;
    for (std::size_t k = 0; k < path.size(); ++k) {
      const UpdateResult3 ra = m.update(a, path[k], size, SnapBackPolicy::Stop);
      const UpdateResult3 rb = m.update(b, rotateStrain3(path[k], r), size, SnapBackPolicy::Stop);
      ASSERT_TRUE(ra.converged() && rb.converged()) << "increment " << k;
      EXPECT_LE((rotateStress3(ra.stress, r) - rb.stress).cwiseAbs().maxCoeff(), 1e-10 * test::kFt) << "increment " << k;
      EXPECT_NEAR(a.damage(), b.damage(), 1e-10);
    }
    ASSERT_TRUE(a.band && b.band);
    EXPECT_NEAR(std::abs((r * a.band->crackNormal).dot(b.band->crackNormal)), 1.0, 1e-12);
    EXPECT_GT(a.damage(), 0.5);
  }
}

// Random in-plane strain paths (loading, unloading, compression, rotating axes), 1e-6..1e-4.
std::vector<Eigen::Vector3d> randomPlanePath(std::mt19937_64& rng, int n) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const auto uni = [&](double a, double b) { return a + (b - a) * u(rng); };
  std::vector<Eigen::Vector3d> out;
  Eigen::Vector3d dir = Eigen::Vector3d(uni(-0.3, 1.0), uni(-0.5, 0.5), uni(-0.5, 0.5)).normalized();
  while (static_cast<int>(out.size()) < n) {
    const int kind = static_cast<int>(uni(0.0, 4.0));
    const int length = 1 + static_cast<int>(uni(0.0, 8.0));
    if (kind == 1) dir = -dir;
    if (kind == 2) dir = Eigen::Vector3d(-std::abs(uni(0.2, 1.0)), uni(-1.0, 0.2), uni(-0.3, 0.3)).normalized();
    for (int i = 0; i < length && static_cast<int>(out.size()) < n; ++i) {
      if (kind == 3) dir = rotateStrain(dir, uni(0.05, 0.4)).normalized();
      out.push_back(std::pow(10.0, uni(-6.0, -4.0)) * dir);
    }
  }
  return out;
}

TEST(TwoPhasePoint3D, PlaneStrainIn3DIsThe2DPlaneStrainPointOnRandomPaths) {
  // eps_zz = gamma_yz = gamma_xz = 0: the 3D point is the 2D plane-strain point, whose driving
  // force takes the 3D split (docs/model.md, "The point in 3D", (a)). In-plane stresses to
  // 1e-10 f_t' on random paths with compression and rotating axes; sigma_zz = nu (sxx + syy) in
  // the bulk while intact.
  std::mt19937_64 rng(7);
  const Material m2(params3(test::kNu, Hypothesis::PlaneStrain));
  const Material3D m3(params3());
  int cracked = 0, compared = 0;
  for (int path = 0; path < 60; ++path) {
    const double h = std::pow(10.0, 0.5 + 1.5 * std::uniform_real_distribution<double>(0.0, 1.0)(rng));  // 3..100 mm
    MaterialPoint p2;
    MaterialPoint3 p3;
    for (const Eigen::Vector3d& d : randomPlanePath(rng, 40)) {
      const UpdateResult r2 = m2.update(p2, d, EffectiveSize::fixed(h), SnapBackPolicy::Stop);
      const UpdateResult3 r3 = m3.update(p3, fromInPlane(d), EffectiveSize3::fixed(h), SnapBackPolicy::Stop);
      ASSERT_EQ(r2.converged(), r3.converged());
      if (!r2.converged()) break;
      ++compared;
      EXPECT_LE((inPlane(r3.stress) - r2.stress).cwiseAbs().maxCoeff(), 1e-10 * test::kFt);
      EXPECT_NEAR(p2.damage(), p3.damage(), 1e-9);
      if (!p3.band) {
        EXPECT_NEAR(r3.stress[2], test::kNu * (r3.stress[0] + r3.stress[1]), 1e-10 * test::kFt);
      }
    }
    cracked += p3.band.has_value();
  }
  EXPECT_GT(cracked, 20);
  EXPECT_GT(compared, 1500);
}

TEST(TwoPhasePoint3D, UniaxialTensionWithoutPoissonIsThe2DPlaneStressCurveAlongAnyAxis) {
  // nu = 0: uniaxial strain is uniaxial stress (no lateral stress), and the 3D band along any
  // direction d gives the 2D plane-stress point's curve (which is the 1D law, Eqs. (11)-(13)),
  // to 1e-10 f_t', through onset, softening past the peak, unloading and reloading.
  std::mt19937_64 rng(3);
  const Material m2(params3(0.0, Hypothesis::PlaneStress));
  const Material3D m3(params3(0.0));
  std::vector<double> path(80, 3e-6);
  for (int i = 0; i < 10; ++i) path.push_back(-4e-6);
  for (int i = 0; i < 30; ++i) path.push_back(6e-6);
  for (int trial = 0; trial < 4; ++trial) {
    const Vec3 d = trial == 0 ? Vec3(Vec3::UnitX()) : Vec3(randomRotation(rng).col(0));
    MaterialPoint p2;
    MaterialPoint3 p3;
    for (double de : path) {
      const UpdateResult r2 = m2.update(p2, Voigt(de, 0.0, 0.0), EffectiveSize::fixed(10.0), SnapBackPolicy::Stop);
      const UpdateResult3 r3 = m3.update(p3, uniaxialStrain(d, de), EffectiveSize3::fixed(10.0), SnapBackPolicy::Stop);
      ASSERT_TRUE(r2.converged() && r3.converged());
      const Voigt6 expected = stressVoigt(r2.stress[0] * d * d.transpose());  // sigma d (x) d
      EXPECT_LE((r3.stress - expected).cwiseAbs().maxCoeff(), 1e-10 * test::kFt);
    }
    EXPECT_GT(p3.damage(), 0.1);
  }
}

// One uniaxial-stress increment under mixed control: eps_xx += dExx, the five other stress
// components held at zero (Newton on their strains with the consistent tangent's block).
bool uniaxialStressStep3(const Material3D& m, MaterialPoint3& p, double dExx, const EffectiveSize3& size,
                         Voigt6& stress) {
  UpdateOptions options(SnapBackPolicy::Stop);
  options.stressControlled = 0b111110u;
  Voigt6 d = Voigt6::Zero();
  d[0] = dExx;
  d[1] = d[2] = -m.params().elastic.poissonRatio * dExx;
  for (int it = 0; it < 50; ++it) {
    MaterialPoint3 trial = p;
    const UpdateResult3 r = m.update(trial, d, size, options);
    if (!r.converged()) return false;
    const Eigen::Matrix<double, 5, 1> res = r.stress.tail<5>();
    if (res.norm() <= 1e-11 * test::kFt) {
      p = trial;
      stress = r.stress;
      return true;
    }
    d.tail<5>() -= r.tangent.bottomRightCorner<5, 5>().partialPivLu().solve(res);
  }
  return false;
}

// Closed form of the 3D uniaxial-stress band with nu > 0 (docs/model.md, "The point in 3D",
// (b)): normal x, the band's lateral strains yy and zz both frozen at eps0 = -nu f_t'/E; its
// effective stress stays non-negative, so Y = eps_L : a : eps_L / 2 = F(x) (Eq. 12):
//   (lambda + 2 mu) e^2 + 4 lambda eps0 e + 4 (lambda + mu) eps0^2 = 2 F(x),
// sigma = x ((lambda + 2 mu) e + 2 lambda eps0) (Eq. 11), eps_xx = sigma / E + w / H with
// w = h (e - sigma / E) (the bulk is in uniaxial stress).
UniaxialBandPoint uniaxialBand3D(double nu, double x) {
  const double e = test::kE, mu = e / (2 * (1 + nu)), lambda = e * nu / ((1 + nu) * (1 - 2 * nu));
  const double eps0 = -nu * test::kFt / e, a11 = lambda + 2 * mu;
  const double c = 4 * (lambda + mu) * eps0 * eps0 - 2 * damageFunction(kLaw, x);
  const double normal = (-2 * lambda * eps0 + std::sqrt(4 * lambda * lambda * eps0 * eps0 - a11 * c)) / a11;
  const double stress = x * (a11 * normal + 2 * lambda * eps0);
  return {stress, normal, test::kBandWidth * (normal - stress / e)};
}

TEST(TwoPhasePoint3D, UniaxialStressFollowsItsClosedFormAndThe2DCurveWithoutPoisson) {
  // Uniaxial stress (the five other stress components held at zero): for nu = 0 the 2D
  // plane-stress closed form (material/uniaxial_closed_form.hpp), for nu = 0.2 the 3D one above:
  // stress and macro strain at the point's own integrity, to 1e-10 f_t' (and 1e-10 f_t' / E).
  for (double nu : {0.0, test::kNu}) {
    const Material3D m(params3(nu));
    const double bigH = 10.0;
    MaterialPoint3 p;
    Voigt6 stress;
    int checked = 0;
    // Elastic steps, one exactly to the onset strain f_t' / E (so the band opens on the uniaxial
    // state, as ecm-point's onset row does), then softening.
    const double onset = test::kFt / test::kE;
    for (int i = 0; i < 150; ++i) {
      const double d = i < 46 ? 2e-6 : i == 46 ? onset - p.strain[0] : 4e-6;
      ASSERT_TRUE(uniaxialStressStep3(m, p, d, EffectiveSize3::fixed(bigH), stress)) << i;
      if (!p.band) continue;
      const double x = p.band->integrity;
      const UniaxialBandPoint c = nu == 0.0 ? uniaxialBandResponse(kLaw, 0.0, test::kBandWidth, x) : uniaxialBand3D(nu, x);
      EXPECT_NEAR(stress[0], c.stress, 1e-10 * test::kFt) << "nu " << nu << " x " << x;
      EXPECT_NEAR(p.strain[0], uniaxialMacroStrain(c, test::kE, bigH), 1e-10 * test::kFt / test::kE);
      ++checked;
    }
    EXPECT_GT(checked, 80);
    EXPECT_LT(p.band->integrity, 0.3);
  }
  // With nu = 0.2 the 3D curve departs from the 2D plane-stress one after onset ((b)): the
  // 2D band's zz strain is free. Its peak: 3.057 MPa (2D) against the 3D closed form's.
  double peak2 = 0.0, peak3 = 0.0;
  for (double lx = 0.0; lx > -3.0; lx -= 1e-4) {
    peak2 = std::max(peak2, uniaxialBandResponse(kLaw, test::kNu, test::kBandWidth, std::pow(10.0, lx)).stress);
    peak3 = std::max(peak3, uniaxialBand3D(test::kNu, std::pow(10.0, lx)).stress);
  }
  EXPECT_GT(peak3, peak2 + 0.01);
}

TEST(TwoPhasePoint3D, DissipatesTheFractureEnergyPerUnitAreaForNormalsAlongAndOffTheAxes) {
  // Identity (docs/model.md): H x dissipation = h int_0^1 F dD = G_F, in uniaxial strain along
  // x and along off-axis directions (the effective stress of the band stays non-negative, the
  // split removes nothing), to 1e-3.
  const Material3D m(params3());
  const double bigH = 2.5, gf = test::kBandWidth * dissipationToFailure(kLaw);
  std::mt19937_64 rng(11);
  for (int trial = 0; trial < 3; ++trial) {
    const Vec3 d = trial == 0 ? Vec3(Vec3::UnitX()) : Vec3(randomRotation(rng).col(1));
    MaterialPoint3 p;
    double dissipated = 0.0, e = 0.0, de = 1e-7;
    while (e < 20.0 * test::kBandWidth / bigH + 1e-2) {
      const UpdateResult3 r = m.update(p, uniaxialStrain(d, de), EffectiveSize3::fixed(bigH), SnapBackPolicy::Stop);
      ASSERT_TRUE(r.converged()) << e;
      dissipated += r.dissipation;
      e += de;
      if (p.band) de *= 1.02;
    }
    ASSERT_TRUE(p.band);
    EXPECT_NEAR(std::abs(p.band->crackNormal.dot(d)), 1.0, 1e-12);
    EXPECT_NEAR(bigH * dissipated, gf, 1e-3 * gf) << "direction " << d.transpose();
  }
}

// Relative error of the consistent tangent against central differences of the update.
double tangentError3(const Material3D& m, const MaterialPoint3& p, const Voigt6& d, const EffectiveSize3& size) {
  MaterialPoint3 q = p;
  const UpdateResult3 r = m.update(q, d, size, SnapBackPolicy::Stop);
  EXPECT_TRUE(r.converged());
  Tangent6 fd;
  const double delta = 1e-9;
  for (int j = 0; j < 6; ++j) {
    Voigt6 e = Voigt6::Zero();
    e[j] = delta;
    MaterialPoint3 a = p, b = p;
    const UpdateResult3 ra = m.update(a, d + e, size, SnapBackPolicy::Stop), rb = m.update(b, d - e, size, SnapBackPolicy::Stop);
    EXPECT_TRUE(ra.converged() && rb.converged());
    fd.col(j) = (ra.stress - rb.stress) / (2.0 * delta);
  }
  return (r.tangent - fd).cwiseAbs().maxCoeff() / r.tangent.cwiseAbs().maxCoeff();
}

TEST(TwoPhasePoint3D, TangentMatchesFiniteDifferencesInEveryRegime) {
  // Eq. (10) in 3D against central differences (MTest's numerical tangent check), relative
  // error <= 1e-6: elastic, softening, unloading, reloading, and sliding in two directions.
  const Material3D m(params3());
  const auto size = EffectiveSize3::fixed(2.5);
  Voigt6 tension;
  tension << 1.0, 0.1, 0.15, 0.05, 0.1, 0.2;  // principal axes off the grid axes
  MaterialPoint3 p;
  const auto load = [&](const Voigt6& d, int steps) {
    for (int i = 0; i < steps; ++i) ASSERT_TRUE(m.update(p, d / steps, size, SnapBackPolicy::Stop).converged());
  };
  EXPECT_LT(tangentError3(m, p, 5e-5 * tension, size), 1e-6) << "elastic";
  load(1.2e-4 * tension, 20);
  ASSERT_TRUE(p.band);
  EXPECT_LT(tangentError3(m, p, 2e-6 * tension, size), 1e-6) << "softening";
  load(1e-5 * tension, 5);
  EXPECT_LT(tangentError3(m, p, -2e-5 * tension, size), 1e-6) << "unloading";
  load(-4e-5 * tension, 5);
  EXPECT_LT(tangentError3(m, p, 2e-5 * tension, size), 1e-6) << "reloading";
  load(3e-5 * tension, 5);
  Voigt6 shear;
  shear << 1.0, 0.0, 0.0, 0.6, 0.8, 1.0;
  const double before = p.damage();
  MaterialPoint3 q = p;
  ASSERT_TRUE(m.update(q, 1e-5 * shear, size, SnapBackPolicy::Stop).converged());
  ASSERT_GT(q.damage(), before);
  EXPECT_LT(tangentError3(m, p, 1e-5 * shear, size), 1e-6) << "mixed mode";
}

TEST(TwoPhasePoint3D, RandomPathsKeepThePhysics) {
  // Random 3D strain paths (fixed seed) over effective sizes 0.06 mm .. 2 m: a failed update
  // leaves the state unchanged; a converged one has finite stress and tangent, dissipation >= 0,
  // damage never decreasing; traction continuity, Eq. (6), to 1e-9 f_t'; the band stress inside
  // the strength envelope Y(sigma_L) <= F(0) (x^2 F(x) <= F(0) for Eq. (13)); at loading states
  // well inside a regime the tangent matches central differences to 1e-5.
  std::mt19937_64 rng(2026);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const Material3D m(params3());
  const double onsetY = test::kFt * test::kFt / (2.0 * test::kE);
  int converged = 0, cracked = 0, tangents = 0;
  for (int path = 0; path < 300; ++path) {
    const auto size = EffectiveSize3::fixed(std::pow(10.0, std::log10(0.06) + u(rng) * (std::log10(2000.0) - std::log10(0.06))));
    Voigt6 dir;
    for (int i = 0; i < 6; ++i) dir[i] = 2.0 * u(rng) - 0.6;
    dir.normalize();
    MaterialPoint3 p;
    for (int k = 0; k < 40; ++k) {
      if (u(rng) < 0.15) dir = -dir;
      if (u(rng) < 0.15) dir = rotateStrain3(dir, randomRotation(rng));
      const Voigt6 d = std::pow(10.0, -6.0 + 2.0 * u(rng)) * dir;
      const MaterialPoint3 before = p;
      const UpdateResult3 r = m.update(p, d, size, SnapBackPolicy::Stop);
      if (!r.converged()) {
        ASSERT_EQ(p.strain, before.strain);
        ASSERT_EQ(p.band.has_value(), before.band.has_value());
        if (p.band) {
          ASSERT_TRUE(p.band->jump == before.band->jump && p.band->integrity == before.band->integrity);
        }
        continue;
      }
      ++converged;
      ASSERT_TRUE(r.stress.allFinite() && r.tangent.allFinite() && std::isfinite(r.dissipation));
      ASSERT_GE(r.dissipation, 0.0);
      ASSERT_GE(p.damage(), before.damage());
      if (!p.band) continue;
      const TwoPhasePoint3D& e = *m.enriched();
      const BandEquilibrium3 eq =
          e.equilibrium(*p.band, BandDamageLaw::LoadingSurface{p.band->integrity, INFINITY}, p.strain, p.band->jump, false);
      ASSERT_LE(eq.residual.norm(), 1e-9 * test::kFt + 1e-13 * (m.stiffness() * p.strain).norm());
      ASSERT_LE(drivingForceValue3(eq.band.stress, test::kE, test::kNu), onsetY * (1.0 + 1e-9));
      ASSERT_LE((eq.stress - r.stress).norm(), 1e-9 * test::kFt);
      if (p.damage() > before.damage() && before.damage() > 0.0 && size.value < 50.0 && u(rng) < 0.3) {
        const double delta = 1e-8;
        Tangent6 fd;
        bool smooth = true;
        for (int j = 0; j < 6 && smooth; ++j) {
          Voigt6 dj = Voigt6::Zero();
          dj[j] = delta;
          MaterialPoint3 a = before, b = before;
          const UpdateResult3 ra = m.update(a, d + dj, size, SnapBackPolicy::Stop), rb = m.update(b, d - dj, size, SnapBackPolicy::Stop);
          smooth = ra.converged() && rb.converged() && a.damage() > before.damage() && b.damage() > before.damage();
          fd.col(j) = (ra.stress - rb.stress) / (2.0 * delta);
        }
        // Away from the kink of Y where a principal effective stress of the band crosses zero.
        const Eigen::SelfAdjointEigenSolver<Mat3> es(stressTensor(eq.band.stress / p.band->integrity));
        smooth = smooth && es.eigenvalues().cwiseAbs().minCoeff() > 1e-3 * es.eigenvalues().cwiseAbs().maxCoeff();
        if (smooth) {
          ++tangents;
          EXPECT_LT((r.tangent - fd).cwiseAbs().maxCoeff() / r.tangent.cwiseAbs().maxCoeff(), 1e-5);
        }
      }
    }
    cracked += p.band.has_value();
  }
  EXPECT_GT(converged, 10000);
  EXPECT_GT(cracked, 100);
  EXPECT_GT(tangents, 20);
}

TEST(TwoPhasePoint3D, AnIntactUpdateIsTheProductWithTheStiffness) {
  // updateIntact's fast path (the cheap bound, docs/performance.md) computes its bound from the
  // stress's registers and copies the tangent by packets: its stress must be stiffness * strain
  // bit for bit and its tangent the stiffness, as updateIntactSlow's. Random strains up to 0.3 x
  // and 1.2 x the uniaxial onset strain, increments up to a quarter of it: both paths are taken
  // (counted by |sigma| below and above f_t' / 2).
  const TwoPhasePoint3D model(params3().enriched());
  std::mt19937_64 rng(20261204);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double onset = test::kFt / test::kE;
  const auto size = EffectiveSize3::fixed(2.5);
  long fast = 0, slow = 0;
  for (int k = 0; k < 20000; ++k) {
    Voigt6 strain, d;
    const double scale = k % 2 ? 1.2 : 0.3;
    for (int c = 0; c < 6; ++c) strain[c] = scale * onset * u(rng), d[c] = 0.25 * scale * onset * u(rng);
    const Voigt6 end = strain + d;
    const Voigt6 product = model.stiffness() * end;
    const bool surely = model.onsetFraction(strain, d) == std::nullopt &&
                        model.onsetFraction(Voigt6::Zero(), strain) == std::nullopt;
    std::optional<BandState3> opened;
    const UpdateResult3 r = model.updateIntact(strain, d, size, opened, SnapBackPolicy::Stop);
    if (opened || !surely) continue;
    ASSERT_TRUE(r.converged());
    for (int c = 0; c < 6; ++c) ASSERT_EQ(std::bit_cast<std::uint64_t>(r.stress[c]), std::bit_cast<std::uint64_t>(product[c])) << k;
    ASSERT_TRUE(r.tangent == model.stiffness()) << k;
    ASSERT_TRUE(strain == end) << k;
    ++(product.head<3>().squaredNorm() + 2.0 * product.tail<3>().squaredNorm() < 0.25 * test::kFt * test::kFt ? fast : slow);
  }
  EXPECT_GT(fast, 1000);
  EXPECT_GT(slow, 100);
}

TEST(TwoPhasePoint3D, RefusesASecondBandAndA2DHypothesis) {
  MaterialParams p = params3();
  p.secondBand = SecondBandOption::Orthogonal;
  EXPECT_THROW(Material3D{p}, ParameterError);
  EXPECT_THROW(Material3D{params3(test::kNu, Hypothesis::PlaneStress)}, ParameterError);
  EXPECT_THROW(Material{params3()}, ParameterError);
}

TEST(EffectiveSize3, SectionRuleIsTheCellSizeAlongAnAxisAndTheCubeRootRuleIsIsotropic) {
  // H = V / A(n): a 2 x 3 x 4 cell cut normal to x has the 3 x 4 section, H = 2; along the
  // cube's diagonal (1,1,1) a unit cube's central section is the regular hexagon of side
  // sqrt(2)/2, area 3 sqrt(3) / 4, so H = 4 / (3 sqrt(3)).
  EffectiveSize3 s{EffectiveSizeRule3::Oriented, 0.0, {2.0, 3.0, 4.0}};
  EXPECT_NEAR(s(Vec3::UnitX()), 2.0, 1e-14);
  EXPECT_NEAR(s(Vec3::UnitZ()), 4.0, 1e-14);
  EffectiveSize3 cube{EffectiveSizeRule3::Oriented, 0.0, {1.0, 1.0, 1.0}};
  EXPECT_NEAR(cube(Vec3(1, 1, 1).normalized()), 4.0 / (3.0 * std::sqrt(3.0)), 1e-14);
  // normal (1,1,0)/sqrt2 in a unit cube: the section is sqrt(2) x 1, H = 1/sqrt(2) (Fig. 2's diagonal)
  EXPECT_NEAR(cube(Vec3(1, 1, 0).normalized()), 1.0 / std::sqrt(2.0), 1e-14);
  EffectiveSize3 root{EffectiveSizeRule3::CubeRoot, 0.0, {2.0, 4.0, 1.0}};
  EXPECT_NEAR(root(Vec3::UnitY()), 2.0, 1e-14);
}

}  // namespace
}  // namespace ecm

// Where the two largest principal stresses are equal, the crack normal is the first of the x, y,
// z axes not normal to their eigenspace, projected onto it (docs/model.md, "Equal principal
// stresses"), as the 2D point takes x for an equibiaxial stress: the same answer on every
// machine, not the eigen-solver's arbitrary vector of the plane.
namespace ecm {
namespace {
TEST(EqualPrincipalStresses, TheNormalIsTheFirstAxisProjectedOntoTheirPlane) {
  const auto normal = [](const Voigt6& s) { return canonicalNormal3(largestPrincipal(s).firstDirection); };
  EXPECT_NEAR((normal(Voigt6(1, 1, 0, 0, 0, 0)) - Vec3(1, 0, 0)).norm(), 0.0, 1e-12);   // sxx = syy
  EXPECT_NEAR((normal(Voigt6(0, 1, 1, 0, 0, 0)) - Vec3(0, 1, 0)).norm(), 0.0, 1e-12);   // syy = szz
  EXPECT_NEAR((normal(Voigt6(1, 0, 1, 0, 0, 0)) - Vec3(1, 0, 0)).norm(), 0.0, 1e-12);   // sxx = szz
  EXPECT_NEAR((normal(Voigt6(2, 2, 2, 0, 0, 0)) - Vec3(1, 0, 0)).norm(), 0.0, 1e-12);   // hydrostatic
  // A plane off the axes: a stress 3 (x) 3 on n1 = (0, 1, 1)/sqrt2 and n2 = (1, 0, 0): x is in it.
  const Vec3 n1 = Vec3(0, 1, 1).normalized();
  const Mat3 t = 3.0 * (n1 * n1.transpose() + Vec3(1, 0, 0) * Vec3(1, 0, 0).transpose());
  EXPECT_NEAR((normal(Voigt6(t(0, 0), t(1, 1), t(2, 2), t(1, 2), t(0, 2), t(0, 1))) - Vec3(1, 0, 0)).norm(), 0.0, 1e-12);
  // Distinct values keep their own direction.
  EXPECT_NEAR((normal(Voigt6(1, 1.5, 0, 0, 0, 0)) - Vec3(0, 1, 0)).norm(), 0.0, 1e-12);
}
}  // namespace
}  // namespace ecm
