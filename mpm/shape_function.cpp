#include "mpm/shape_function.hpp"

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
  switch (f) {
    case ShapeFunction::Linear: return computeStencil<ShapeFunction::Linear>(grid, inv, halfWidth, x, s);
    case ShapeFunction::UGimp: return computeStencil<ShapeFunction::UGimp>(grid, inv, halfWidth, x, s);
    case ShapeFunction::BSpline2: return computeStencil<ShapeFunction::BSpline2>(grid, inv, halfWidth, x, s);
  }
  return false;
}

void expandStencil(ShapeFunction f, const StencilAt& at, const Vec2& invCell, const Vec2& halfWidth, Stencil& s) {
  switch (f) {
    case ShapeFunction::Linear: return expandStencil<ShapeFunction::Linear>(at, invCell, halfWidth, s);
    case ShapeFunction::UGimp: return expandStencil<ShapeFunction::UGimp>(at, invCell, halfWidth, s);
    case ShapeFunction::BSpline2: return expandStencil<ShapeFunction::BSpline2>(at, invCell, halfWidth, s);
  }
}

}  // namespace ecm::mpm
