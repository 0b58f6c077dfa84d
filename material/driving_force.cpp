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

}  // namespace ecm
