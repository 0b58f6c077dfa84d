#include "material/driving_force.hpp"

#include <algorithm>
#include <cmath>

namespace ecm {

DrivingForce drivingForce(const Voigt& s, const Tangent& c) {
  const Principal pr = principalStresses(s);
  const double p1 = std::max(pr.first, 0.0), p2 = std::max(pr.second, 0.0);
  // Isotropic compliance in the principal frame: c11 on the diagonal, c12 off it.
  const double c11 = c(0, 0), c12 = c(0, 1);
  DrivingForce y;
  y.value = 0.5 * (c11 * (p1 * p1 + p2 * p2) + 2.0 * c12 * p1 * p2);  // Eq. (12)
  if (y.value == 0.0) return y;
  // One-sided at a principal stress that is zero (to round-off): counted as opening. This is
  // the band's loading side: at onset in uniaxial stress the lateral effective stress is zero
  // and grows with the opening (through nu), so its compliance coupling c12 p1 is active.
  const double zero = -1e-9 * std::max(std::abs(pr.first), std::abs(pr.second));
  const double dy1 = pr.first >= zero ? c11 * p1 + c12 * p2 : 0.0;
  const double dy2 = pr.second >= zero ? c11 * p2 + c12 * p1 : 0.0;
  const Vec2& n1 = pr.firstDirection;
  const Vec2 n2(-n1[1], n1[0]);
  // d p_i / d sigma_voigt = [n_x^2, n_y^2, 2 n_x n_y]
  y.stressGradient = dy1 * Voigt(n1[0] * n1[0], n1[1] * n1[1], 2.0 * n1[0] * n1[1]) +
                     dy2 * Voigt(n2[0] * n2[0], n2[1] * n2[1], 2.0 * n2[0] * n2[1]);
  return y;
}

DrivingForce drivingForcePlaneStrain(const Voigt& s, double e, double nu) {
  const Principal pr = principalStresses(s);
  const double p[3] = {pr.first, pr.second, nu * (s[0] + s[1])};
  DrivingForce y;
  y.value = drivingForceOfPrincipal(p[0], p[1], p[2], e, nu);  // Eq. (12)
  if (y.value == 0.0) return y;
  // dY/dp_i, one-sided at a principal value that is zero to round-off (counted as opening).
  const double zero = -1e-9 * std::max({std::abs(p[0]), std::abs(p[1]), std::abs(p[2])});
  const double pp[3] = {std::max(p[0], 0.0), std::max(p[1], 0.0), std::max(p[2], 0.0)};
  double dy[3];
  for (int i = 0; i < 3; ++i) dy[i] = p[i] >= zero ? (pp[i] - nu * (pp[0] + pp[1] + pp[2] - pp[i])) / e : 0.0;
  // sigma_zz = nu (sxx + syy) = nu (p1 + p2): its gradient is nu (n1 (x) n1 + n2 (x) n2).
  const Vec2& n1 = pr.firstDirection;
  const Vec2 n2(-n1[1], n1[0]);
  y.stressGradient = (dy[0] + nu * dy[2]) * normalProjector(n1) + (dy[1] + nu * dy[2]) * normalProjector(n2);
  return y;
}

}  // namespace ecm
