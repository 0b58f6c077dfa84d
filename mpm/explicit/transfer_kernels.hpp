#pragma once
// One particle's share of the transfers, shared by the separate phases (transfer.cpp) and the
// fused USL pass (fused_transfer.cpp): its scatter to the nodes of its stencil, its gather from
// them; and what both do around them. Internal to mpm/.
#include <algorithm>
#include <cstddef>
#include <limits>
#include <utility>

#include "mpm/core/grid.hpp"
#include "mpm/core/particles.hpp"
#include "mpm/core/shape_function.hpp"
#include "mpm/scene/scene.hpp"

namespace ecm::mpm::detail {

// Where a scatter accumulates (the grid's fields).
struct ScatterTarget {
  double* mass;
  Vec2* momentum;
  Vec2* force;
  Vec2* externalForce;
};

inline ScatterTarget targetOf(GridFields& g) {
  return {g.mass.data(), g.momentum.data(), g.force.data(), g.externalForce.data()};
}

// Zeroes what a scatter accumulates (mass and momentum, forces) at every node; keepMass: not the mass.
void zeroScatterFields(int threads, GridFields& grid, bool massMomentum, bool forces, bool keepMass = false);
// Moves the threads' lists into `into` (appended) and sorts it.
void mergeSorted(std::vector<std::vector<std::uint32_t>>& perThread, std::vector<std::uint32_t>& into);
// The failures of the transfers, as SimulationError (step: the steps taken).
[[noreturn]] void throwNotFinite(long step, const Particles& particles, std::size_t p);
[[noreturn]] void throwLeftGrid(const Scene& scene, long step, const Particles& particles, std::size_t p);

inline constexpr std::size_t kNoParticle = std::numeric_limits<std::size_t>::max();

// Whether a particle's velocity and position are finite: Eigen's allFinite() became a call where
// the compiler stopped inlining in these loops (measured: the MUSL remap 45 % slower).
// Branch-free, as Eigen's: y - y is 0 for a finite y and NaN otherwise, and NaN != NaN.
inline bool finiteMotion(const Vec2& v, const Vec2& x) {
  const double zero = (v[0] - v[0]) + (v[1] - v[1]) + (x[0] - x[0]) + (x[1] - x[1]);
  return zero == zero;
}

// The particle range of part t of n (for the gathers: each particle on its own, any split gives the same bits).
inline std::pair<std::size_t, std::size_t> partRange(std::size_t count, int t, int n) {
  return {count * static_cast<std::size_t>(t) / static_cast<std::size_t>(n),
          count * static_cast<std::size_t>(t + 1) / static_cast<std::size_t>(n)};
}

// A particle's mass m, momentum m v, internal force (-V sigma . grad N) and gravity at the
// nodes of its stencil s (nx: nodes per grid row). The fields come as values: the fused pass
// hands over the stress it has just computed (reloading it from memory straight after the
// store stalls on store forwarding).
// Mass = false (with MassMomentum): the momentum alone, for MUSL's remap (its mass is the P2G's).
template <ShapeFunction F, bool MassMomentum, bool Forces, bool Mass = MassMomentum>
inline void scatterParticle(const Stencil& s, int nx, double m, const Vec2& velocity, double volume, const Voigt& sig,
                            const Vec2& gravity, bool withGravity, ScatterTarget out) {
  constexpr int S = supportSize(F);
  const Vec2 mv = m * velocity;
  const double sxx = volume * sig[0], syy = volume * sig[1], sxy = volume * sig[2];
  const Vec2 mg = m * gravity;
  for (int j = 0; j < S; ++j) {
    const int row = s.base + j * nx;
    for (int k = 0; k < S; ++k) {
      const int n = row + k;
      const double w = s.wx[k] * s.wy[j];
      if constexpr (MassMomentum) {
        if constexpr (Mass) out.mass[n] += w * m;
        out.momentum[n] += w * mv;
      }
      if constexpr (Forces) {
        const double gx = s.gx[k] * s.wy[j], gy = s.wx[k] * s.gy[j];
        out.force[n] -= Vec2(sxx * gx + sxy * gy, sxy * gx + syy * gy);
        if (withGravity) out.externalForce[n] += w * mg;
      }
    }
  }
}

// The same for particle i of p.
template <ShapeFunction F, bool MassMomentum, bool Forces, bool Mass = MassMomentum>
inline void scatterParticle(const Stencil& s, int nx, const Particles& p, std::size_t i, const Vec2& gravity,
                            bool withGravity, ScatterTarget out) {
  scatterParticle<F, MassMomentum, Forces, Mass>(s, nx, p.mass[i], p.velocity[i], p.volume[i], p.stress[i], gravity,
                                           withGravity, out);
}

// What a particle reads from the updated grid: the velocity v^{n+1} and its change at the
// particle, and (WithStrain) the velocity gradient L = sum v_n (x) grad N_n.
struct Gathered {
  Vec2 velocity = Vec2::Zero(), velocityChange = Vec2::Zero();
  double lxx = 0.0, lxy = 0.0, lyx = 0.0, lyy = 0.0;
};

// Where a gather reads (the grid's updated velocities), as plain pointers.
struct GatherSource {
  const Vec2* velocity;
  const Vec2* velocityChange;
};

inline GatherSource sourceOf(const GridFields& g) { return {g.velocity.data(), g.velocityChange.data()}; }

template <ShapeFunction F, bool WithStrain>
inline Gathered gatherParticle(const Stencil& s, int nx, GatherSource grid) {
  constexpr int S = supportSize(F);
  Gathered g;
  for (int j = 0; j < S; ++j) {
    const int row = s.base + j * nx;
    for (int k = 0; k < S; ++k) {
      const auto n = static_cast<std::size_t>(row + k);
      const double w = s.wx[k] * s.wy[j];
      const Vec2& vn = grid.velocity[n];
      g.velocity += w * vn;
      g.velocityChange += w * grid.velocityChange[n];
      if constexpr (WithStrain) {
        const double gx = s.gx[k] * s.wy[j], gy = s.wx[k] * s.gy[j];
        g.lxx += vn[0] * gx, g.lxy += vn[0] * gy, g.lyx += vn[1] * gx, g.lyy += vn[1] * gy;
      }
    }
  }
  return g;
}

template <ShapeFunction F, bool WithStrain>
inline Gathered gatherParticle(const Stencil& s, int nx, const GridFields& grid) {
  return gatherParticle<F, WithStrain>(s, nx, sourceOf(grid));
}

// The strain increment of the step from the velocity gradient (engineering shear).
inline Voigt strainIncrement(const Gathered& g, double dt) {
  return Voigt(dt * g.lxx, dt * g.lyy, dt * (g.lxy + g.lyx));
}

}  // namespace ecm::mpm::detail
