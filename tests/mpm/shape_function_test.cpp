// Shape functions: partition of unity, reproduction of linear fields (sum grad N = 0,
// sum x_I (x) grad N_I = I), uGIMP against a numerical average of the hat function over the
// particle domain (its definition, Bardenhagen & Kober 2004), B-spline against its closed form.
#include <gtest/gtest.h>

#include <random>

#include "mpm/core/shape_function.hpp"

namespace ecm::mpm {
namespace {

double hat(double d) { return std::max(0.0, 1.0 - std::abs(d)); }

class Shapes : public ::testing::TestWithParam<ShapeFunction> {};

TEST_P(Shapes, PartitionOfUnityAndLinearReproduction) {
  const Grid g{Vec2(-3.0, 2.0), Vec2(2.0, 0.5), 8, 10};
  const Vec2 half(0.25, 0.25);
  const int s = supportSize(GetParam());
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> ux(-3.0 + 2.0 * 1.6, -3.0 + 16.0 - 2.0 * 1.6), uy(2.0 + 0.8, 7.0 - 0.8);
  for (int trial = 0; trial < 200; ++trial) {
    const Vec2 x(ux(rng), uy(rng));
    Stencil st;
    ASSERT_TRUE(computeStencil(GetParam(), g, half, x, st));
    double sum = 0.0;
    Vec2 grad = Vec2::Zero(), interp = Vec2::Zero();
    Mat2 id = Mat2::Zero();
    for (int j = 0; j < s; ++j)
      for (int k = 0; k < s; ++k) {
        const int n = st.base + j * g.nodesX() + k;
        const double w = st.wx[k] * st.wy[j];
        const Vec2 gn(st.gx[k] * st.wy[j], st.wx[k] * st.gy[j]);
        EXPECT_GE(w, 0.0);
        sum += w;
        grad += gn;
        interp += w * g.nodePosition(n);
        id += g.nodePosition(n) * gn.transpose();
      }
    EXPECT_NEAR(sum, 1.0, 1e-14);
    EXPECT_NEAR(grad.norm(), 0.0, 1e-12);
    EXPECT_NEAR((id - Mat2::Identity()).norm(), 0.0, 1e-12);
    EXPECT_NEAR((interp - x).norm(), 0.0, 1e-12);  // all three reproduce linear fields
  }
}

INSTANTIATE_TEST_SUITE_P(All, Shapes,
                         ::testing::Values(ShapeFunction::Linear, ShapeFunction::UGimp, ShapeFunction::BSpline2),
                         [](const auto& info) { return std::string(toString(info.param)); });

TEST(Shapes, UGimpIsTheHatAveragedOverTheParticleDomain) {
  const Grid g{Vec2::Zero(), Vec2(1.0, 1.0), 6, 6};
  const double l = 0.25;  // k = 2
  for (double xi : {1.1, 1.25, 1.5, 1.74, 1.76, 2.0, 2.9}) {
    Stencil st;
    ASSERT_TRUE(computeStencil(ShapeFunction::UGimp, g, Vec2(l, l), Vec2(xi, 3.3), st));
    const int base = st.base % g.nodesX();
    for (int k = 0; k < 3; ++k) {
      const int m = 20000;  // midpoint rule over [xi - l, xi + l]
      double avg = 0.0, slope = 0.0;
      for (int q = 0; q < m; ++q) avg += hat(xi - l + (q + 0.5) * 2.0 * l / m - (base + k)) / m;
      slope = (hat(xi + l - (base + k)) - hat(xi - l - (base + k))) / (2.0 * l);  // d/dx of the average
      EXPECT_NEAR(st.wx[k], avg, 1e-8) << "xi " << xi << " node " << base + k;
      EXPECT_NEAR(st.gx[k], slope, 1e-12) << "xi " << xi << " node " << base + k;
    }
  }
}

TEST(Shapes, QuadraticBSplineClosedForm) {
  const Grid g{Vec2::Zero(), Vec2(1.0, 1.0), 6, 6};
  auto b = [](double d) {
    d = std::abs(d);
    return d < 0.5 ? 0.75 - d * d : (d < 1.5 ? 0.5 * (1.5 - d) * (1.5 - d) : 0.0);
  };
  for (double xi : {1.5, 1.7, 2.2, 2.49, 3.0}) {
    Stencil st;
    ASSERT_TRUE(computeStencil(ShapeFunction::BSpline2, g, Vec2::Zero(), Vec2(xi, 3.0), st));
    const int base = st.base % g.nodesX();
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(st.wx[k], b(xi - (base + k)), 1e-14);
  }
}

TEST(Shapes, OutsideTheGridIsRefused) {
  const Grid g{Vec2::Zero(), Vec2(1.0, 1.0), 6, 6};
  Stencil st;
  EXPECT_FALSE(computeStencil(ShapeFunction::Linear, g, Vec2::Zero(), Vec2(-0.01, 3.0), st));
  EXPECT_TRUE(computeStencil(ShapeFunction::Linear, g, Vec2::Zero(), Vec2(6.0, 3.0), st));
  EXPECT_FALSE(computeStencil(ShapeFunction::UGimp, g, Vec2(0.25, 0.25), Vec2(0.2, 3.0), st));
  EXPECT_FALSE(computeStencil(ShapeFunction::BSpline2, g, Vec2::Zero(), Vec2(3.0, 0.4), st));
  EXPECT_FALSE(computeStencil(ShapeFunction::Linear, g, Vec2::Zero(), Vec2(NAN, 3.0), st));
}

}  // namespace
}  // namespace ecm::mpm
