#pragma once
// 3D Voigt algebra: vectors [xx, yy, zz, yz, xz, xy]; strains carry engineering shears
// (gamma_ij = 2 eps_ij). The 3D counterpart of material/voigt.hpp (docs/model.md, "The point in 3D").
#include <cmath>

#include <Eigen/Dense>

namespace ecm {

using Voigt6 = Eigen::Matrix<double, 6, 1>;    // stress [sxx, syy, szz, syz, sxz, sxy] or strain [exx, eyy, ezz, gyz, gxz, gxy]
using Tangent6 = Eigen::Matrix<double, 6, 6>;  // d stress / d strain
using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
using JumpMap3 = Eigen::Matrix<double, 6, 3>;

// Isotropic stiffness a (Voigt, engineering shears) and its inverse.
inline Tangent6 isotropicStiffness3(double youngsModulus, double nu) {
  const double mu = youngsModulus / (2.0 * (1.0 + nu));
  const double lambda = youngsModulus * nu / ((1.0 + nu) * (1.0 - 2.0 * nu));
  Tangent6 a = Tangent6::Zero();
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) a(i, j) = lambda;
    a(i, i) = lambda + 2.0 * mu;
    a(i + 3, i + 3) = mu;
  }
  return a;
}
inline Tangent6 isotropicCompliance3(double youngsModulus, double nu) {
  Tangent6 c = Tangent6::Zero();
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) c(i, j) = -nu / youngsModulus;
    c(i, i) = 1.0 / youngsModulus;
    c(i + 3, i + 3) = 2.0 * (1.0 + nu) / youngsModulus;
  }
  return c;
}

// The symmetric tensor of a Voigt stress, and back.
inline Mat3 stressTensor(const Voigt6& s) {
  Mat3 t;
  t << s[0], s[5], s[4],
       s[5], s[1], s[3],
       s[4], s[3], s[2];
  return t;
}
inline Voigt6 stressVoigt(const Mat3& t) {
  Voigt6 s;
  s << t(0, 0), t(1, 1), t(2, 2), t(1, 2), t(0, 2), t(0, 1);
  return s;
}
// d p / d sigma_voigt for p = n . sigma n: [n_x^2, n_y^2, n_z^2, 2 n_y n_z, 2 n_x n_z, 2 n_x n_y].
inline Voigt6 normalProjector3(const Vec3& n) {
  Voigt6 p;
  p << n[0] * n[0], n[1] * n[1], n[2] * n[2], 2.0 * n[1] * n[2], 2.0 * n[0] * n[2], 2.0 * n[0] * n[1];
  return p;
}

// Sign convention for a crack normal (docs/model.md pitfall 5): first non-zero component positive.
inline Vec3 canonicalNormal3(Vec3 n) {
  n.normalize();
  if (n[0] < 0.0 || (n[0] == 0.0 && (n[1] < 0.0 || (n[1] == 0.0 && n[2] < 0.0)))) n = -n;
  return n;
}

// N such that sym(n (x) [u]) = N [u] in Voigt strain (Eq. 3), and traction t = sigma n = N^T sigma.
inline JumpMap3 jumpToStrain3(const Vec3& n) {
  JumpMap3 m;
  m << n[0], 0.0, 0.0,
       0.0, n[1], 0.0,
       0.0, 0.0, n[2],
       0.0, n[2], n[1],
       n[2], 0.0, n[0],
       n[1], n[0], 0.0;
  return m;
}

// Rotation of Voigt stress and strain by the rotation matrix r (sigma' = r sigma r^T).
inline Voigt6 rotateStress3(const Voigt6& s, const Mat3& r) { return stressVoigt(r * stressTensor(s) * r.transpose()); }
inline Voigt6 rotateStrain3(const Voigt6& e, const Mat3& r) {
  Voigt6 half = e;
  half.tail<3>() *= 0.5;
  Voigt6 out = rotateStress3(half, r);
  out.tail<3>() *= 2.0;
  return out;
}

// 2D Voigt [xx, yy, xy] as the in-plane part of a 3D one, and back.
inline Voigt6 fromInPlane(const Eigen::Vector3d& v, double zz = 0.0) {
  Voigt6 out;
  out << v[0], v[1], zz, 0.0, 0.0, v[2];
  return out;
}
inline Eigen::Vector3d inPlane(const Voigt6& v) { return {v[0], v[1], v[5]}; }

}  // namespace ecm
