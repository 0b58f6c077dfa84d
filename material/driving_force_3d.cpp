#include "material/driving_force_3d.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Eigenvalues>

namespace ecm {

namespace {

// +1: all principal values >= 0; -1: all <= 0; 0: mixed signs. A symmetric tensor's
// eigenvalues are all non-negative exactly when its three invariants are.
int principalSigns(const Voigt6& s) {
  const double i1 = s[0] + s[1] + s[2];
  const double i2 = s[0] * s[1] + s[1] * s[2] + s[0] * s[2] - s[3] * s[3] - s[4] * s[4] - s[5] * s[5];
  const double i3 = s[0] * (s[1] * s[2] - s[3] * s[3]) - s[5] * (s[5] * s[2] - s[3] * s[4]) +
                    s[4] * (s[5] * s[3] - s[1] * s[4]);
  if (i2 < 0.0) return 0;
  if (i1 >= 0.0 && i3 >= 0.0) return 1;
  if (i1 <= 0.0 && i3 <= 0.0) return -1;
  return 0;
}

// sigma : a^-1 : sigma / 2 for the isotropic compliance, Eq. (12) with nothing split off.
double wholeDrivingForce(const Voigt6& s, double e, double nu) {
  const double tr = s[0] + s[1] + s[2];
  const double ss = s.head<3>().squaredNorm() + 2.0 * s.tail<3>().squaredNorm();
  return 0.5 / e * ((1.0 + nu) * ss - nu * tr * tr);
}

}  // namespace

DrivingForce3 drivingForce3(const Voigt6& s, double e, double nu) {
  DrivingForce3 y;
  const int signs = principalSigns(s);
  if (signs < 0) return y;
  if (signs > 0) {
    y.value = wholeDrivingForce(s, e, nu);
    const double tr = s[0] + s[1] + s[2];
    y.stressGradient.head<3>() = ((1.0 + nu) * s.head<3>().array() - nu * tr).matrix() / e;  // a^-1 sigma
    y.stressGradient.tail<3>() = 2.0 * (1.0 + nu) / e * s.tail<3>();                          // engineering shears
    return y;
  }
  const Eigen::SelfAdjointEigenSolver<Mat3> es(stressTensor(s));
  const Vec3 p = es.eigenvalues();
  y.value = drivingForceOfPrincipal(p[0], p[1], p[2], e, nu);
  if (y.value == 0.0) return y;
  const double zero = -1e-9 * p.cwiseAbs().maxCoeff();
  const Vec3 pp = p.cwiseMax(0.0);
  for (int i = 0; i < 3; ++i) {
    if (p[i] < zero) continue;
    const double dy = (pp[i] - nu * (pp.sum() - pp[i])) / e;
    y.stressGradient += dy * normalProjector3(es.eigenvectors().col(i));
  }
  return y;
}

double drivingForceValue3(const Voigt6& s, double e, double nu) {
  const int signs = principalSigns(s);
  if (signs < 0) return 0.0;
  if (signs > 0) return wholeDrivingForce(s, e, nu);
  const Eigen::SelfAdjointEigenSolver<Mat3> es(stressTensor(s), Eigen::EigenvaluesOnly);
  const Vec3 p = es.eigenvalues();
  return drivingForceOfPrincipal(p[0], p[1], p[2], e, nu);
}

Principal3 largestPrincipal(const Voigt6& s) {
  const Eigen::SelfAdjointEigenSolver<Mat3> es(stressTensor(s));
  const Vec3 p = es.eigenvalues();
  // Where the largest value is repeated (to round-off), any direction of its eigenspace is one:
  // take the first of the x, y and z axes that is not normal to the eigenspace, projected onto it,
  // as the 2D point takes x for an equibiaxial stress (docs/model.md, "Equal principal stresses").
  const double roundOff = 64.0 * std::numeric_limits<double>::epsilon() * p.cwiseAbs().maxCoeff();
  if (!(p[2] - p[1] <= roundOff)) return {p[2], es.eigenvectors().col(2)};
  const int from = p[2] - p[0] <= roundOff ? 0 : 1;  // (a hydrostatic stress: every direction)
  for (int axis = 0; axis < 3; ++axis) {
    Vec3 d = Vec3::Zero();
    for (int k = from; k < 3; ++k) d += es.eigenvectors()(axis, k) * es.eigenvectors().col(k);
    if (d.norm() > 1e-6) return {p[2], d.normalized()};
  }
  return {p[2], es.eigenvectors().col(2)};
}

}  // namespace ecm
