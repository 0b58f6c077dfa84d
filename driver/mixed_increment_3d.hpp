#pragma once
// Mixed control in 3D: the increment that meets a segment's targets with a stiffness k, shared
// by ecm's 3D point (point_driver_3d.cpp) and a loaded UMAT (umat_driver.cpp).
#include <array>
#include <vector>

#include <Eigen/Dense>

#include "driver/load_path.hpp"
#include "material/material_3d.hpp"

namespace ecm::driver {

// Bit i set: component i is stress-controlled.
inline unsigned stressMask(const std::array<Control, 6>& c) {
  unsigned m = 0;
  for (int i = 0; i < 6; ++i)
    if (c[i] == Control::Stress) m |= 1u << i;
  return m;
}

// The increment meeting the targets with the stiffness k: strain components as given, the
// stress-controlled ones from k_ss d_s = (target - current)_s - k_sk d_k.
inline Voigt6 mixedIncrement(const Tangent6& k, const Voigt6& current, const std::array<Control, 6>& control,
                             const Voigt6& strainIncrement, const Voigt6& stressTarget) {
  std::vector<int> s, e;
  for (int i = 0; i < 6; ++i) (control[i] == Control::Stress ? s : e).push_back(i);
  Voigt6 d = Voigt6::Zero();
  for (int i : e) d[i] = strainIncrement[i];
  if (s.empty()) return d;
  const int n = static_cast<int>(s.size());
  Eigen::MatrixXd kss(n, n);
  Eigen::VectorXd rhs(n);
  for (int a = 0; a < n; ++a) {
    rhs[a] = stressTarget[s[a]] - current[s[a]];
    for (int i : e) rhs[a] -= k(s[a], i) * d[i];
    for (int b = 0; b < n; ++b) kss(a, b) = k(s[a], s[b]);
  }
  const Eigen::VectorXd ds = kss.partialPivLu().solve(rhs);
  for (int a = 0; a < n; ++a) d[s[a]] = ds[a];
  return d;
}

}  // namespace ecm::driver
