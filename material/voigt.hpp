#pragma once
// 2D Voigt algebra: vectors [xx, yy, xy]; strains carry engineering shear (gamma_xy = 2 eps_xy).
#include <Eigen/Dense>

namespace ecm {

using Voigt = Eigen::Vector3d;    // stress [sxx, syy, sxy] or strain [exx, eyy, gxy]
using Tangent = Eigen::Matrix3d;  // d stress / d strain
using Vec2 = Eigen::Vector2d;
using Mat2 = Eigen::Matrix2d;
using JumpMap = Eigen::Matrix<double, 3, 2>;

// ThreeDimensional: six strain components (material/voigt3.hpp, Material3D); the 2D callers refuse it.
enum class Hypothesis { PlaneStress, PlaneStrain, ThreeDimensional };
inline const char* toString(Hypothesis h) {
  switch (h) {
    case Hypothesis::PlaneStress: return "plane_stress";
    case Hypothesis::PlaneStrain: return "plane_strain";
    case Hypothesis::ThreeDimensional: return "three_dimensional";
  }
  return "?";
}

// Principal values (first >= second) and the unit direction of the first one.
struct Principal {
  double first;
  double second;
  Vec2 firstDirection;
};

// Closed-form eigen-decomposition of a symmetric 2x2 stress given in Voigt form (no trigonometry).
inline Principal principalStresses(const Voigt& s) {
  const double mean = 0.5 * (s[0] + s[1]);
  const double halfDiff = 0.5 * (s[0] - s[1]);
  const double radius = std::sqrt(halfDiff * halfDiff + s[2] * s[2]);
  if (radius == 0.0) return {mean, mean, Vec2(1.0, 0.0)};
  // Eigenvector of the first value from whichever row of (sigma - p1 I) is better conditioned.
  const Vec2 v = halfDiff >= 0.0 ? Vec2(halfDiff + radius, s[2]) : Vec2(s[2], radius - halfDiff);
  return {mean + radius, mean - radius, v.normalized()};
}

// Sign convention for a crack normal (docs/model.md pitfall 5): first non-zero component positive.
inline Vec2 canonicalNormal(Vec2 n) {
  n.normalize();
  if (n[0] < 0.0 || (n[0] == 0.0 && n[1] < 0.0)) n = -n;
  return n;
}

// N such that sym(n (x) [u]) = N [u] in Voigt strain (Eq. 3), and traction t = sigma.n = N^T sigma.
inline JumpMap jumpToStrain(const Vec2& n) {
  JumpMap m;
  m << n[0], 0.0,
       0.0, n[1],
       n[1], n[0];
  return m;
}

// Rotation of Voigt stress and strain by angle theta (counter-clockwise), for objectivity checks.
inline Voigt rotateStress(const Voigt& s, double theta) {
  const double c = std::cos(theta), q = std::sin(theta);
  Mat2 r;
  r << c, -q, q, c;
  Mat2 t;
  t << s[0], s[2], s[2], s[1];
  const Mat2 u = r * t * r.transpose();
  return {u(0, 0), u(1, 1), u(0, 1)};
}
inline Voigt rotateStrain(const Voigt& e, double theta) {
  const Voigt half(e[0], e[1], 0.5 * e[2]);
  const Voigt r = rotateStress(half, theta);
  return {r[0], r[1], 2.0 * r[2]};
}

}  // namespace ecm
