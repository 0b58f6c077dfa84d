// libecm_umat.so called exactly as a finite element code calls a UMAT (Fortran convention, the
// state round trip through STATEV, trial iterations of a global Newton from the same start),
// against the material library's own point (Material3D, Material): equal to 1e-12.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "driver/point_driver_3d.hpp"
#include "material/material.hpp"
#include "material/material_3d.hpp"
#include "umat/umat.h"
#include "umat/umat_layout.hpp"
#include "../paper_constants.hpp"

namespace ecm {
namespace {

using namespace ecm::umat;

// The caller's side of a UMAT: what an FE code keeps per integration point and passes per call.
struct Caller {
  int ndi = 3, nshr = 3, ntens = 6, nstatv = kStateCount;
  std::vector<double> props;
  std::vector<double> stress, statev, ddsdde, stran;
  double sse = 0.0, spd = 0.0, pnewdt = 1.0, celent = 0.0;

  Caller(int ndi_, int nshr_, std::vector<double> p) : ndi(ndi_), nshr(nshr_), ntens(ndi_ + nshr_), props(std::move(p)) {
    stress.assign(ntens, 0.0);
    statev.assign(nstatv, 0.0);
    statev[kIntegrity] = 1.0;
    ddsdde.assign(ntens * ntens, 0.0);
    stran.assign(ntens, 0.0);
  }
  // One call from the committed state (nothing is committed): the trial of a Newton iteration.
  struct Trial {
    std::vector<double> stress, statev, ddsdde;
    double sse, spd, pnewdt;
  };
  // `rotation`: DROT (column-major), the identity when not given; `pnewdtIn`: PNEWDT as passed in.
  Trial call(const std::vector<double>& dstran, const double* rotation = nullptr, double pnewdtIn = 1.0) const {
    Trial t{stress, statev, ddsdde, sse, spd, pnewdtIn};
    double scd = 0, rpl = 0, ddsddt[6] = {}, drplde[6] = {}, drpldt = 0, time[2] = {0, 0}, dtime = 1, temp = 0, dtemp = 0;
    double predef = 0, dpred = 0, coords[3] = {}, drot[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1}, dfgrd[9] = {};
    if (rotation) std::copy(rotation, rotation + 9, drot);
    const int nprops = static_cast<int>(props.size()), noel = 1, npt = 1, layer = 1, kspt = 1, kstep[4] = {1, 1, 0, 0}, kinc = 1;
    const char cmname[80] = "ABAQUS_ECM";
    umat_(t.stress.data(), t.statev.data(), t.ddsdde.data(), &t.sse, &t.spd, &scd, &rpl, ddsddt, drplde, &drpldt,
          stran.data(), dstran.data(), time, &dtime, &temp, &dtemp, &predef, &dpred, cmname, &ndi, &nshr, &ntens, &nstatv,
          props.data(), &nprops, coords, drot, &t.pnewdt, &celent, dfgrd, dfgrd, &noel, &npt, &layer, &kspt, kstep, &kinc,
          80);
    return t;
  }
  // Converged increment: the FE code keeps the last trial's outputs and adds DSTRAN to STRAN.
  Trial commit(const std::vector<double>& dstran) {
    const Trial t = call(dstran);
    stress = t.stress, statev = t.statev, ddsdde = t.ddsdde, sse = t.sse, spd = t.spd;
    for (int i = 0; i < ntens; ++i) stran[i] += dstran[i];
    return t;
  }
};

// model, E, nu, f_t', E_p, n, h, H, snap_back (release), substep levels
std::vector<double> concreteProps(double bigH, double snapBack = 1.0) {
  return {1.0, test::kE, test::kNu, test::kFt, test::kEp, test::kN, test::kBandWidth, bigH, snapBack, 10.0};
}

MaterialParams concrete(Hypothesis h) {
  MaterialParams p = test::paperConcreteMaterial();
  p.elastic.hypothesis = h;
  return p;
}

// Tension along x past the peak, unloading, then shear in 12 and 23 (Abaqus order 11, 22, 33, 12, 13, 23).
std::vector<std::array<double, 6>> pathAbaqus() {
  std::vector<std::array<double, 6>> path;
  for (int i = 0; i < 50; ++i) path.push_back({4e-6, -0.2e-6, -0.1e-6, 0.3e-6, 0, 0});
  for (int i = 0; i < 10; ++i) path.push_back({-3e-6, 0, 0, 0, 0, 0});
  for (int i = 0; i < 40; ++i) path.push_back({1e-6, 0, 0, 1.5e-5, 0.4e-5, 0.8e-5});
  return path;
}

TEST(Umat, ThreeDimensionalIsTheMaterialPointIncrementByIncrement) {
  // NTENS = 6: stresses, DDSDDE, STATEV, SSE and SPD against Material3D driven with the same
  // strains (shears 12, 13, 23 -> xy, xz, yz), to 1e-12 relative; two trial calls per increment
  // (a global Newton's iterations) leave nothing behind.
  Caller c(3, 3, concreteProps(10.0));
  const Material3D m(concrete(Hypothesis::ThreeDimensional));
  MaterialPoint3 p;
  double dissipated = 0.0;
  for (const auto& a : pathAbaqus()) {
    std::vector<double> d(a.begin(), a.end());
    std::vector<double> off = d;
    off[0] *= 1.7;
    c.call(off);  // an earlier Newton iterate: its outputs are dropped
    const Caller::Trial t = c.commit(d);
    Voigt6 e;
    for (int i = 0; i < 6; ++i) e[kAbaqusToEcm6[i]] = d[i];
    const UpdateResult3 r = m.update(p, e, EffectiveSize3::fixed(10.0), UpdateOptions(SnapBackPolicy::Release));
    ASSERT_TRUE(r.converged());
    dissipated += r.dissipation;
    ASSERT_EQ(t.pnewdt, 1.0);
    const double scale = r.stress.cwiseAbs().maxCoeff() + 1e-3 * test::kFt;
    for (int i = 0; i < 6; ++i) {
      EXPECT_NEAR(t.stress[i], r.stress[kAbaqusToEcm6[i]], 1e-12 * scale);
      for (int j = 0; j < 6; ++j)
        EXPECT_NEAR(t.ddsdde[i + 6 * j], r.tangent(kAbaqusToEcm6[i], kAbaqusToEcm6[j]), 1e-12 * test::kE);
    }
    EXPECT_NEAR(t.statev[kDissipation], dissipated, 1e-12 * (dissipated + 1e-12));
    EXPECT_EQ(t.spd, t.statev[kDissipation]);
    EXPECT_NEAR(t.sse, m.storedEnergy(p), 1e-12 * (m.storedEnergy(p) + 1e-12));
    EXPECT_EQ(t.statev[kCracked], p.band ? 1.0 : 0.0);
    if (p.band) {
      EXPECT_NEAR(t.statev[kIntegrity], p.band->integrity, 1e-12);
    }
  }
  ASSERT_TRUE(p.band);
  EXPECT_GT(p.damage(), 0.5);
}

TEST(Umat, DdsddeIsTheDerivativeOfStressInAbaqusOrder) {
  // Central differences of STRESS over DSTRAN, column by column (engineering shears): the
  // component maps of stress, strain and DDSDDE agree (relative 1e-6) in softening.
  Caller c(3, 3, concreteProps(2.5));
  for (int i = 0; i < 40; ++i) c.commit({3e-6, 0.5e-6, 0.2e-6, 1e-6, 0.5e-6, 0.8e-6});
  ASSERT_EQ(c.statev[kCracked], 1.0);
  const std::vector<double> d{2e-6, 0.3e-6, 0.1e-6, 1.2e-6, 0.4e-6, 0.9e-6};
  const Caller::Trial t = c.call(d);
  double worst = 0.0, largest = 0.0;
  for (int j = 0; j < 6; ++j) {
    std::vector<double> up = d, down = d;
    up[j] += 1e-9, down[j] -= 1e-9;
    const Caller::Trial a = c.call(up), b = c.call(down);
    for (int i = 0; i < 6; ++i) {
      worst = std::max(worst, std::abs((a.stress[i] - b.stress[i]) / 2e-9 - t.ddsdde[i + 6 * j]));
      largest = std::max(largest, std::abs(t.ddsdde[i + 6 * j]));
    }
  }
  EXPECT_LT(worst / largest, 1e-6);
}

TEST(Umat, PlaneStressIsThe2DPointAndPlaneStrainThe3DOne) {
  // NTENS = 3 (11, 22, 12): the 2D plane-stress point, to 1e-12 (docs/model.md, (b)).
  // NTENS = 4 (11, 22, 33, 12) with eps_33 = 0: the 3D point in plane strain, which is the 2D
  // plane-strain point (docs/model.md, (a)), to 1e-10 f_t'.
  Caller ps(2, 1, concreteProps(10.0));
  Caller pe(3, 1, concreteProps(10.0));
  const Material m2(concrete(Hypothesis::PlaneStress)), m2e(concrete(Hypothesis::PlaneStrain));
  MaterialPoint p, q;
  for (int k = 0; k < 100; ++k) {
    const Voigt d = k < 60 ? Voigt(4e-6, -0.5e-6, 1e-6) : Voigt(0.5e-6, 0.0, 1e-5);
    const Caller::Trial a = ps.commit({d[0], d[1], d[2]});
    const Caller::Trial b = pe.commit({d[0], d[1], 0.0, d[2]});
    const UpdateResult r = m2.update(p, d, EffectiveSize::fixed(10.0), UpdateOptions(SnapBackPolicy::Release));
    const UpdateResult s = m2e.update(q, d, EffectiveSize::fixed(10.0), UpdateOptions(SnapBackPolicy::Release));
    ASSERT_TRUE(r.converged() && s.converged());
    for (int i = 0; i < 3; ++i) {
      EXPECT_NEAR(a.stress[i], r.stress[i], 1e-12 * (r.stress.cwiseAbs().maxCoeff() + 1e-3));
      EXPECT_NEAR(b.stress[i == 2 ? 3 : i], s.stress[i], 1e-10 * test::kFt);
    }
  }
  EXPECT_GT(p.damage(), 0.5);
  EXPECT_GT(q.damage(), 0.5);
}

TEST(Umat, AsksForASmallerIncrementAtASnapBackItMustNotRelease) {
  // H = 500 mm lies beyond the snap-back size (195.55 mm in 1D, docs/model.md): a large
  // increment past the peak snaps back. With snap_back = 0 (stop) PNEWDT < 1 and the state
  // stays; with 1 (release) the band lands on its stable branch and PNEWDT stays 1.
  for (double policy : {0.0, 1.0}) {
    Caller c(3, 3, concreteProps(500.0, policy));
    c.commit({test::kFt / test::kE, 0, 0, 0, 0, 0});
    const Caller::Trial t = c.call({2e-4, 0, 0, 0, 0, 0});
    if (policy == 0.0) {
      EXPECT_LT(t.pnewdt, 1.0);
      EXPECT_EQ(t.statev, c.statev);
    } else {
      EXPECT_EQ(t.pnewdt, 1.0);
      EXPECT_EQ(t.statev[kCracked], 1.0);
      EXPECT_LT(t.stress[0], 0.5 * test::kFt);
    }
  }
}

TEST(Umat, AsksCalculixForASmallerIncrementToo) {
  // CalculiX passes PNEWDT = -1 for "no request" and cuts the increment back only when a
  // material returns a positive value (its checkconvergence.c): the request must be 0.5, not
  // min(-1, 0.5). Abaqus passes a large value; both read 0.5 as "half the increment".
  Caller c(3, 3, concreteProps(500.0, 0.0));
  c.commit({test::kFt / test::kE, 0, 0, 0, 0, 0});
  EXPECT_EQ(c.call({2e-4, 0, 0, 0, 0, 0}, nullptr, -1.0).pnewdt, 0.5);
  EXPECT_EQ(c.call({2e-4, 0, 0, 0, 0, 0}, nullptr, 1e36).pnewdt, 0.5);
  EXPECT_EQ(c.call({2e-4, 0, 0, 0, 0, 0}, nullptr, 0.25).pnewdt, 0.25);  // a smaller request stands
  EXPECT_EQ(c.call({-1e-5, 0, 0, 0, 0, 0}, nullptr, -1.0).pnewdt, -1.0);  // a converged update asks nothing
}

TEST(Umat, BadPropsStopTheAnalysisWithTheReason) {
  // Bad input stops the analysis (exit status 2, io/cli_exit.hpp) naming the entry.
  auto props = concreteProps(10.0);
  props[kTensileStrength] = -1.0;
  EXPECT_EXIT(Caller(3, 3, props).call(std::vector<double>(6, 0.0)), ::testing::ExitedWithCode(2), "tensile_strength");
  props = concreteProps(10.0);
  props.resize(5);
  EXPECT_EXIT(Caller(3, 3, props).call(std::vector<double>(6, 0.0)), ::testing::ExitedWithCode(2), "NPROPS = 5");
  props = concreteProps(0.0);
  EXPECT_EXIT(Caller(3, 3, props).call(std::vector<double>(6, 0.0)), ::testing::ExitedWithCode(2), "CELENT");
  props = concreteProps(0.01);
  EXPECT_EXIT(Caller(3, 3, props).call(std::vector<double>(6, 0.0)), ::testing::ExitedWithCode(2), "PROPS\\(8\\)");
  props = concreteProps(10.0);
  props[kSnapBack] = 2.0;
  EXPECT_EXIT(Caller(3, 3, props).call(std::vector<double>(6, 0.0)), ::testing::ExitedWithCode(2), "PROPS\\(9\\)");
  EXPECT_EXIT(Caller(2, 2, concreteProps(10.0)).call(std::vector<double>(4, 0.0)), ::testing::ExitedWithCode(2), "NSHR");
  // A denormal E: the strain at onset f_t' / E is infinite (found by fuzz/fuzz_umat.cpp: the update
  // crawled through its sub-steps).
  props = concreteProps(10.0);
  props[kYoungsModulus] = 4.9e-324;
  EXPECT_EXIT(Caller(3, 3, props).call(std::vector<double>(6, 0.0)), ::testing::ExitedWithCode(2), "strain at onset");
}

TEST(Umat, WhatAFiniteElementCodeCouldPassWrongIsRefusedByName) {
  // Found by fuzz/fuzz_umat.cpp: each of these was accepted before (NaN stresses, a normal that
  // is not one, a band state no update writes).
  const double nan = std::nan("");
  // A strain increment that is not a number (a diverging global Newton): a smaller increment is
  // asked for and nothing changes.
  Caller c(3, 3, concreteProps(10.0));
  c.commit({1e-5, 0, 0, 0, 0, 0});
  const Caller::Trial t = c.call({nan, 0, 0, 0, 0, 0});
  EXPECT_EQ(t.pnewdt, 0.5);
  EXPECT_EQ(t.statev, c.statev);
  EXPECT_EQ(t.stress, c.stress);
  // Nor is a rotation that is not a number; one that is not a rotation stops the analysis.
  const double nanRotation[9] = {nan, 0, 0, 0, 1, 0, 0, 0, 1}, shear[9] = {1, 0, 0, 0.5, 1, 0, 0, 0, 1};
  EXPECT_EQ(c.call({1e-6, 0, 0, 0, 0, 0}, nanRotation).pnewdt, 0.5);
  EXPECT_EXIT(c.call({1e-6, 0, 0, 0, 0, 0}, shear), ::testing::ExitedWithCode(2), "DROT is not a rotation");
  // STATEV and STRAN that no update of ecm's writes (an initial condition, a corrupted restart)
  // stop it, naming the entry (1-based, as in the input deck).
  Caller bad = c;
  bad.statev[kCracked] = 1.0, bad.statev[kVolumeFraction] = 0.005;  // cracked, with a zero normal
  EXPECT_EXIT(bad.call({1e-6, 0, 0, 0, 0, 0}), ::testing::ExitedWithCode(2), "STATEV\\(3\\) = 0: a cracked point's normal");
  bad = c;
  bad.statev[kCracked] = 0.5;
  EXPECT_EXIT(bad.call({1e-6, 0, 0, 0, 0, 0}), ::testing::ExitedWithCode(2), "STATEV\\(1\\) = 0.5");
  bad = c;
  bad.statev[kJump + 1] = nan;
  EXPECT_EXIT(bad.call({1e-6, 0, 0, 0, 0, 0}), ::testing::ExitedWithCode(2), "STATEV\\(7\\) = nan: not a number");
  bad = c;
  bad.stran[2] = nan;
  EXPECT_EXIT(bad.call({1e-6, 0, 0, 0, 0, 0}), ::testing::ExitedWithCode(2), "STRAN\\(3\\) = nan");
  // An increment whose stress overflows a double is a failed update, not an infinite stress.
  EXPECT_EQ(c.call({1.7e308, 0, 0, 0, 0, 0}).pnewdt, 0.5);
  // STATEV(17), D, is an output: an intact point writes 0 over whatever the caller set.
  Caller stale = c;
  stale.statev[kDamage] = -5.0;
  EXPECT_EQ(stale.call({1e-6, 0, 0, 0, 0, 0}).statev[kDamage], 0.0);
  // Plane stress: a cracked point's normal is in the plane.
  Caller plane(2, 1, concreteProps(10.0));
  plane.statev[kCracked] = 1.0, plane.statev[kNormal] = 0.6, plane.statev[kNormal + 2] = 0.8;
  plane.statev[kVolumeFraction] = 0.005;
  EXPECT_EXIT(plane.call({1e-6, 0, 0}), ::testing::ExitedWithCode(2), "STATEV\\(5\\) = 0.8: plane stress");
}

}  // namespace
}  // namespace ecm

namespace ecm {
namespace {

TEST(Umat, EqualsEcmPointIn3DAlongItsHistory) {
  // ecm-point's 3D run (driver/point_driver_3d.hpp: tension along (1, 2, 2) past the peak, then
  // shear) fed row by row to the UMAT as strain increments: the stresses agree to 1e-12.
  driver::PointScene3 scene;
  scene.name = "umat-vs-point";
  scene.material = concrete(Hypothesis::ThreeDimensional);
  scene.effectiveSize = 2.5;
  scene.path = driver::presetSegments3("rotated_axis", 2e-4, 100, 0.0, Vec3(1, 2, 2));
  driver::Segment3 shear;
  shear.increments = 100;
  shear.target = scene.path.back().target;
  shear.target[5] += 1e-3, shear.target[3] += 4e-4;
  scene.path.push_back(shear);
  const driver::PointRun3 run = driver::runPoint3D(scene);
  ASSERT_TRUE(run.completed) << run.failure;
  Caller c(3, 3, concreteProps(2.5));
  for (std::size_t k = 1; k < run.history.size(); ++k) {
    const driver::HistoryRow3& row = run.history[k];
    std::vector<double> d(6);
    for (int i = 0; i < 6; ++i) d[i] = row.strain[kAbaqusToEcm6[i]] - c.stran[i];
    const Caller::Trial t = c.commit(d);
    for (int i = 0; i < 6; ++i) c.stran[i] = row.strain[kAbaqusToEcm6[i]];  // the same strain, bit for bit
    for (int i = 0; i < 6; ++i)
      EXPECT_NEAR(t.stress[i], row.stress[kAbaqusToEcm6[i]], 1e-12 * (row.stress.cwiseAbs().maxCoeff() + 1e-3)) << k;
    EXPECT_NEAR(t.spd, row.dissipation, 1e-12 * (row.dissipation + 1e-12));
  }
  EXPECT_GT(run.history.back().damage, 0.5);
}

// A symmetric tensor in Abaqus's 3D order (11, 22, 33, 12, 13, 23), `shear` 2 for engineering
// strains and 1 for stresses, turned by R: R T R^T, back in the same order.
std::vector<double> rotatedAbaqus(const std::vector<double>& v, const Eigen::Matrix3d& r, double shear) {
  Eigen::Matrix3d t;
  t << v[0], v[3] / shear, v[4] / shear, v[3] / shear, v[1], v[5] / shear, v[4] / shear, v[5] / shear, v[2];
  t = r * t * r.transpose();
  return {t(0, 0), t(1, 1), t(2, 2), shear * t(0, 1), shear * t(0, 2), shear * t(1, 2)};
}

// With NLGEOM the caller turns STRESS and STRAN with the increment's rotation DROT and the UMAT
// turns its own state: a cracked point turned rigidly by R and loaded by the turned increment
// answers the turned stress (objectivity: to 1e-12 of f_t'), and its band normal is R n. Without
// the state turned (DROT the identity) the same call answers a stress off by more than 0.1 f_t'.
TEST(Umat, ACrackedPointTurnsWithDrot) {
  Caller a(3, 3, concreteProps(10.0));
  for (int i = 0; i < 50; ++i) a.commit({4e-6, -0.2e-6, -0.1e-6, 0.3e-6, 0, 0});  // past the peak along x
  ASSERT_EQ(a.statev[kCracked], 1.0);
  const Eigen::Matrix3d r = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1.0, 2.0, 2.0).normalized()).toRotationMatrix();
  double drot[9];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) drot[i + 3 * j] = r(i, j);
  Caller b = a;  // the same point, turned: the caller has turned its stress and strain
  b.stran = rotatedAbaqus(a.stran, r, 2.0);
  b.stress = rotatedAbaqus(a.stress, r, 1.0);
  const std::vector<double> d = {2e-6, 0.1e-6, 0.0, 0.4e-6, 0.0, 0.0};
  const Caller::Trial plain = a.call(d);
  const Caller::Trial turned = b.call(rotatedAbaqus(d, r, 2.0), drot);
  const std::vector<double> expected = rotatedAbaqus(plain.stress, r, 1.0);
  for (int i = 0; i < 6; ++i) EXPECT_NEAR(turned.stress[i], expected[i], 1e-12 * test::kFt) << i;
  const Eigen::Vector3d n = r * Eigen::Vector3d(a.statev[kNormal], a.statev[kNormal + 1], a.statev[kNormal + 2]);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(turned.statev[kNormal + i], n[i], 1e-12) << i;
  const Caller::Trial unturned = b.call(rotatedAbaqus(d, r, 2.0));
  double off = 0.0;
  for (int i = 0; i < 6; ++i) off = std::max(off, std::abs(unturned.stress[i] - expected[i]));
  EXPECT_GT(off, 0.1 * test::kFt);
}

}  // namespace
}  // namespace ecm
