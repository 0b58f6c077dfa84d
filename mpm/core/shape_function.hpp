#pragma once
// Shape functions as tensor products of 1D functions. A particle's stencil holds the 1D
// weights and derivatives per direction (S = 2 or 3 nodes each): N_ij = wx[i] wy[j],
// grad N_ij = (gx[i] wy[j], wx[i] gy[j]). Located once per step (StencilAt), expanded where used.
#include <algorithm>
#include <cmath>
#include <cstdint>

#include "mpm/core/grid.hpp"

namespace ecm::mpm {

enum class ShapeFunction {
  Linear,    // bilinear hat functions, support one cell each side
  UGimp,     // uniform GIMP: hat convolved with the particle's initial domain (width cell / k)
  BSpline2,  // quadratic B-spline, support 1.5 cells each side (no boundary modification:
             // scenes with particles within 1.5 cells of the grid edge are refused)
};

const char* toString(ShapeFunction f);

// Nodes per direction of a stencil.
constexpr int supportSize(ShapeFunction f) { return f == ShapeFunction::Linear ? 2 : 3; }

// The one dispatch from the scene's shape function to the compiled kernels: returns
// fn.template operator()<F>() for F = f. Callers pick a kernel once per phase, e.g.
//   withShapeFunction(f, []<ShapeFunction F>() { return &scatter<F>; })
template <class Fn>
decltype(auto) withShapeFunction(ShapeFunction f, Fn&& fn) {
  switch (f) {
    case ShapeFunction::UGimp: return fn.template operator()<ShapeFunction::UGimp>();
    case ShapeFunction::BSpline2: return fn.template operator()<ShapeFunction::BSpline2>();
    case ShapeFunction::Linear: break;
  }
  return fn.template operator()<ShapeFunction::Linear>();
}

struct Stencil {
  std::int32_t base = 0;          // node index of the lower-left node of the stencil
  double wx[3] = {}, wy[3] = {};  // 1D weights
  double gx[3] = {}, gy[3] = {};  // 1D derivatives (1/mm)
};

namespace detail {

// One direction, in two halves. locate1D: from xi (position in cell units from the grid origin)
// the first node `base` of the stencil and r = xi - base (exact); false when the stencil would
// reach outside the grid (cells in this direction; halfWidth: the particle's half-size in cell
// units, uGIMP). weights1D: the 1D weights w and derivatives g (invH = 1 / cell size) from r.
template <ShapeFunction F>
inline bool locate1D(double xi, int cells, double halfWidth, int& base, double& r) {
  if constexpr (F == ShapeFunction::Linear) {
    if (!(xi >= 0.0 && xi <= cells)) return false;
    base = std::min(static_cast<int>(xi), cells - 1);
  } else if constexpr (F == ShapeFunction::BSpline2) {
    if (!(xi >= 0.5 && xi < cells - 0.5)) return false;
    base = static_cast<int>(xi - 0.5);
  } else {
    if (!(xi - halfWidth >= 0.0 && xi + halfWidth <= cells) || cells < 2) return false;
    base = std::clamp(static_cast<int>(std::floor(xi - 0.5)), 0, cells - 2);
  }
  r = xi - base;
  return true;
}

template <ShapeFunction F>
inline void weights1D(double r, double halfWidth, double invH, double* w, double* g) {
  if constexpr (F == ShapeFunction::Linear) {
    w[0] = 1.0 - r, w[1] = r;
    g[0] = -invH, g[1] = invH;
  } else if constexpr (F == ShapeFunction::BSpline2) {
    // r: distance to node `base`, in [0.5, 1.5)
    const double a = 1.5 - r, b = r - 1.0, c = r - 0.5;
    w[0] = 0.5 * a * a, w[1] = 0.75 - b * b, w[2] = 0.5 * c * c;
    g[0] = -a * invH, g[1] = -2.0 * b * invH, g[2] = c * invH;
  } else {
    const double l = halfWidth;
    for (int i = 0; i < 3; ++i) {
      const double d = r - i, ad = std::abs(d), s = d < 0.0 ? -1.0 : 1.0;
      if (ad < l) {
        w[i] = 1.0 - (d * d + l * l) / (2.0 * l), g[i] = -d / l * invH;
      } else if (ad <= 1.0 - l) {
        w[i] = 1.0 - ad, g[i] = -s * invH;
      } else if (ad < 1.0 + l) {
        const double q = 1.0 + l - ad;
        w[i] = q * q / (4.0 * l), g[i] = -s * q / (2.0 * l) * invH;
      } else {
        w[i] = 0.0, g[i] = 0.0;
      }
    }
  }
}

}  // namespace detail

// Where a particle's stencil sits: its first node and its offsets from it in cell units. What
// particles keep between the transfers of a step (24 bytes; the weights are recomputed from it).
struct StencilAt {
  double r[2] = {0.0, 0.0};  // plain doubles: an Eigen Vec2 (16-byte aligned) would pad this to 32 bytes
  std::int32_t base = 0;
};
static_assert(sizeof(StencilAt) == 24);

// Locates the stencil of a particle at x; false when the particle (or its uGIMP domain, or its
// B-spline support) is not inside the grid.
template <ShapeFunction F>
inline bool locateStencil(const Grid& grid, const Vec2& invCell, const Vec2& halfWidth, const Vec2& x, StencilAt& at) {
  const double xi = (x[0] - grid.origin[0]) * invCell[0], eta = (x[1] - grid.origin[1]) * invCell[1];
  int bx = 0, by = 0;
  if (!detail::locate1D<F>(xi, grid.cellsX, halfWidth[0], bx, at.r[0])) return false;
  if (!detail::locate1D<F>(eta, grid.cellsY, halfWidth[1], by, at.r[1])) return false;
  at.base = by * (grid.cellsX + 1) + bx;
  return true;
}

// The weights and derivatives of a located stencil.
template <ShapeFunction F>
inline void expandStencil(const StencilAt& at, const Vec2& invCell, const Vec2& halfWidth, Stencil& s) {
  s.base = at.base;
  detail::weights1D<F>(at.r[0], halfWidth[0], invCell[0], s.wx, s.gx);
  detail::weights1D<F>(at.r[1], halfWidth[1], invCell[1], s.wy, s.gy);
}

// Fills the stencil of a particle at x; false when it is not inside the grid (as locateStencil).
template <ShapeFunction F>
inline bool computeStencil(const Grid& grid, const Vec2& invCell, const Vec2& halfWidth, const Vec2& x, Stencil& s) {
  StencilAt at;
  if (!locateStencil<F>(grid, invCell, halfWidth, x, at)) return false;
  expandStencil<F>(at, invCell, halfWidth, s);
  return true;
}

// Runtime dispatch for tests and setup code (inner loops use the template directly).
bool computeStencil(ShapeFunction f, const Grid& grid, const Vec2& halfWidth, const Vec2& x, Stencil& s);
void expandStencil(ShapeFunction f, const StencilAt& at, const Vec2& invCell, const Vec2& halfWidth, Stencil& s);

}  // namespace ecm::mpm
