#pragma once
// Whether the traction-continuity system of Eq. (9) has a locally unique, stable solution branch:
// its Jacobian K (2x2 in plane, 3x3 in space) has all eigenvalues with positive real part. K is
// not symmetric once the band loads (a_L^T of Eq. (11)), so these are not Cholesky tests.
#include <Eigen/Eigenvalues>
#include <cmath>

#include "material/voigt.hpp"
#include "material/voigt3.hpp"

namespace ecm {

// 2x2: determinant and trace positive.
inline bool positiveDefinite(const Mat2& k) { return k.determinant() > 0.0 && k.trace() > 0.0; }

// 3x3: Routh-Hurwitz on det(s I + K): trace, the sum of principal 2x2 minors m and the
// determinant d positive, and trace m > d.
inline bool positiveDefinite(const Mat3& k) {
  const double t = k.trace();
  const double m = k(0, 0) * k(1, 1) - k(0, 1) * k(1, 0) + k(1, 1) * k(2, 2) - k(1, 2) * k(2, 1) + k(0, 0) * k(2, 2) -
                   k(0, 2) * k(2, 0);
  const double d = k.determinant();
  return t > 0.0 && d > 0.0 && t * m > d;
}

// The smallest real part of K's eigenvalues: positive exactly where positiveDefinite() holds, and
// continuous, so it can be minimised along a path. 2x2 in closed form.
inline double smallestRealEigenvalue(const Mat2& k) {
  const double half = 0.5 * k.trace();
  const double disc = half * half - k.determinant();
  return disc > 0.0 ? half - std::sqrt(disc) : half;
}
template <class Matrix>
double smallestRealEigenvalue(const Matrix& k) {
  return Eigen::EigenSolver<Matrix>(k, false).eigenvalues().real().minCoeff();
}

}  // namespace ecm
