#include "mpm/core/shape_function.hpp"

namespace ecm::mpm {

const char* toString(ShapeFunction f) {
  switch (f) {
    case ShapeFunction::Linear: return "linear";
    case ShapeFunction::UGimp: return "ugimp";
    case ShapeFunction::BSpline2: return "bspline2";
  }
  return "?";
}

bool computeStencil(ShapeFunction f, const Grid& grid, const Vec2& halfWidth, const Vec2& x, Stencil& s) {
  const Vec2 inv(1.0 / grid.cellSize[0], 1.0 / grid.cellSize[1]);
  return withShapeFunction(f, [&]<ShapeFunction F>() { return computeStencil<F>(grid, inv, halfWidth, x, s); });
}

void expandStencil(ShapeFunction f, const StencilAt& at, const Vec2& invCell, const Vec2& halfWidth, Stencil& s) {
  withShapeFunction(f, [&]<ShapeFunction F>() { expandStencil<F>(at, invCell, halfWidth, s); });
}

}  // namespace ecm::mpm
