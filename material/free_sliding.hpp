#pragma once
// The two-band Jacobian K of Eq. (9) where one band slides freely against the other
// (docs/model.md, "Two failed bands"). Where both bands have failed, their tractions vanish and
// the four jumps enter Eq. (6) only through the bulk strain's three components: the sliding of
// one band against the other is free, and K's smallest singular value is the bands' integrity
// (~1e-18 of the rest in the runs that met it). Newton's LU steps then amplify round-off along
// that sliding without bound (jumps of hundreds of mm). Such a K is solved for the least-norm
// step, which leaves the sliding where it is, and the residual is measured over K's range.
// The same K can come before the traction criterion says the bands have failed (jumps so large
// that an integrity of 1e-11 still carries traction): LU's reciprocal condition estimate flags
// those (it is NaN where a pivot is exactly 0), and the singular values decide.
#include <Eigen/LU>
#include <Eigen/SVD>

#include "material/two_phase_point.hpp"

namespace ecm {

// Singular values below this fraction of K's largest count as zero.
inline constexpr double kFreeSlidingRank = 1e-10;

struct FreeSliding {
  bool active = false;  // K is singular to kFreeSlidingRank: least-norm solves
  Eigen::JacobiSVD<Mat4> svd;

  // bothFailed: both bands have failed by the traction criterion (the SVD is then always consulted).
  FreeSliding(const Mat4& k, bool bothFailed);
  // |r| over K's range (the residual along the free sliding is a combination of the bands'
  // tractions alone, which have vanished; Newton cannot move it).
  double rangeNorm(const Vec4& r) const;
};

// K^-1 b, or the least-norm solution where the sliding is free.
template <int Cols>
Eigen::Matrix<double, 4, Cols> solveJumps(const Mat4& k, const Eigen::Matrix<double, 4, Cols>& b, bool bothFailed) {
  const FreeSliding free(k, bothFailed);
  if (!free.active) return k.partialPivLu().solve(b);
  return free.svd.solve(b);
}

}  // namespace ecm
