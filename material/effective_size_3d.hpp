#pragma once
// The effective size H = Omega / A of a material point in 3D (Eq. (1); the 3D reading of the
// paper's Fig. 2, docs/model.md "The point in 3D"): the cell's volume over the area of the
// band's plane through the cell's centre, or the cube root of the volume as the simple rule.
#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "material/voigt3.hpp"

namespace ecm {

enum class EffectiveSizeRule3 {
  Fixed,     // H given directly (the point driver, the UMAT with H in PROPS)
  CubeRoot,  // H = (cell volume)^(1/3)
  Oriented,  // H = cell volume / area of the central section of the cell by the band's plane
};

// The area of the section of a box (edges `cell`) by the plane through its centre with unit
// normal n: the polygon through the plane's crossings of the twelve edges.
inline double centralSectionArea(const Vec3& n, const std::array<double, 3>& cell) {
  std::vector<Vec3> points;
  for (int k = 0; k < 3; ++k) {
    if (n[k] == 0.0) continue;  // edges parallel to the plane: their ends are found on the others
    const int i = (k + 1) % 3, j = (k + 2) % 3;
    for (int si = -1; si <= 1; si += 2)
      for (int sj = -1; sj <= 1; sj += 2) {
        Vec3 p;
        p[i] = 0.5 * si * cell[i];
        p[j] = 0.5 * sj * cell[j];
        p[k] = -(n[i] * p[i] + n[j] * p[j]) / n[k];
        if (std::abs(p[k]) <= 0.5 * cell[k] * (1.0 + 1e-12)) points.push_back(p);
      }
  }
  if (points.size() < 3) return 0.0;
  // Order the crossings by angle about n (the section is convex and contains the centre).
  const Vec3 u = (std::abs(n[0]) < 0.9 ? Vec3::UnitX() : Vec3::UnitY()).cross(n).normalized();
  const Vec3 v = n.cross(u);
  std::sort(points.begin(), points.end(),
            [&](const Vec3& a, const Vec3& b) { return std::atan2(a.dot(v), a.dot(u)) < std::atan2(b.dot(v), b.dot(u)); });
  Vec3 twice = Vec3::Zero();
  for (std::size_t m = 0; m < points.size(); ++m) twice += points[m].cross(points[(m + 1) % points.size()]);
  return 0.5 * std::abs(twice.dot(n));
}

struct EffectiveSize3 {
  EffectiveSizeRule3 rule = EffectiveSizeRule3::Fixed;
  double value = 0.0;                    // H for Fixed (mm)
  std::array<double, 3> cell{0, 0, 0};   // cell edges in x, y, z (mm), for CubeRoot and Oriented

  static EffectiveSize3 fixed(double h) { return {EffectiveSizeRule3::Fixed, h, {0, 0, 0}}; }

  // H for a band with unit normal n.
  double operator()(const Vec3& n) const {
    switch (rule) {
      case EffectiveSizeRule3::Fixed: return value;
      case EffectiveSizeRule3::CubeRoot: return std::cbrt(cell[0] * cell[1] * cell[2]);
      case EffectiveSizeRule3::Oriented: return cell[0] * cell[1] * cell[2] / centralSectionArea(n.normalized(), cell);
    }
    return value;
  }
};

}  // namespace ecm
