#pragma once
// The state of an enriched point's band and its two phases at a trial jump, in plane (PlaneBand:
// three Voigt strains, a jump of two components) or in space (SpaceBand: six and three). The
// 2D point (material/two_phase_point.hpp) and the 3D one (material/two_phase_point_3d.hpp) are
// the same model with these types; the update itself is written once (material/cracked_point.hpp).
#include <concepts>

#include "material/band_damage_law.hpp"
#include "material/update_result_3d.hpp"
#include "material/voigt.hpp"
#include "material/voigt3.hpp"

namespace ecm {

// The band law's response to a 3D band strain (Eqs. (11)-(13)), from the surface of the
// increment (BandResponse is the plane one).
struct BandResponse3 {
  Voigt6 stress = Voigt6::Zero();      // sigma_L = x a eps_L
  Tangent6 tangent = Tangent6::Zero(); // a_L^T: loading (x a + a eps_L dx/deps) or secant (x a)
  double integrity = 1.0;
  double drivingForce = 0.0;           // Y
  bool loading = false;
};

// A point in plane stress or strain: Voigt xx, yy, xy; the jump [u] of two components.
struct PlaneBand {
  using Strain = Voigt;
  using StrainTangent = Tangent;
  using Jump = Vec2;
  using JumpJacobian = Mat2;
  using JumpMap = ecm::JumpMap;
  using Response = BandResponse;
  using Result = UpdateResult;
  // N of Eq. (3): eps_L = eps_0 + N [u] / h.
  static JumpMap jumpMap(const Vec2& normal) { return jumpToStrain(normal); }
};

// A point in space: Voigt xx, yy, zz, yz, xz, xy (material/voigt3.hpp); the jump of three.
struct SpaceBand {
  using Strain = Voigt6;
  using StrainTangent = Tangent6;
  using Jump = Vec3;
  using JumpJacobian = Mat3;
  using JumpMap = JumpMap3;
  using Response = BandResponse3;
  using Result = UpdateResult3;
  static JumpMap jumpMap(const Vec3& normal) { return jumpToStrain3(normal); }
};

// Everything a cracked point carries (72 bytes in plane); an intact point carries none of it.
template <class Space>
struct BandStateIn {
  using Jump = typename Space::Jump;
  Jump crackNormal = Jump::Zero();  // n, fixed at onset (first principal direction)
  Jump jump = Jump::Zero();         // [u] accumulated since onset (mm)
  typename Space::Strain onsetStrain = Space::Strain::Zero();  // strain of both phases at onset; eps_L = this + N [u] / h
  double integrity = 1.0;           // x = 1 - D of the band
  double volumeFraction = 0.0;      // f = h / H, Eq. (1)

  double damage() const { return 1.0 - integrity; }
  double normalJump() const { return crackNormal.dot(jump); }
  Jump slidingJump() const { return jump - normalJump() * crackNormal; }
  // In plane: the band's tangent t = (-n_y, n_x), the direction of sliding.
  Vec2 slidingDirection() const
    requires std::same_as<Space, PlaneBand>
  {
    return {-crackNormal[1], crackNormal[0]};
  }
};
using BandState = BandStateIn<PlaneBand>;
using BandState3 = BandStateIn<SpaceBand>;

// Both phases at a trial (strain, jump): what Newton on traction continuity needs.
template <class Space>
struct BandEquilibriumIn {
  typename Space::Strain bandStrain = Space::Strain::Zero();  // eps_L, Eq. (3) integrated
  typename Space::Response band;                              // sigma_L and its tangent a_L^T, Eqs. (5), (11)
  typename Space::Strain stress = Space::Strain::Zero();      // sigma = a_b : eps_b, Eq. (4) integrated
  typename Space::Jump residual = Space::Jump::Zero();        // (sigma - sigma_L) n, Eq. (6)
  typename Space::JumpJacobian jacobian = Space::JumpJacobian::Zero();  // K = -d residual / d[u] = C / (1 - f), Eq. (9)
};
using BandEquilibrium = BandEquilibriumIn<PlaneBand>;
using BandEquilibrium3 = BandEquilibriumIn<SpaceBand>;

}  // namespace ecm
