#pragma once
// The effective size H = Omega / A of a material point (Eq. (1) and the paper's Fig. 2).
#include <cmath>

#include "material/voigt.hpp"

namespace ecm {

enum class EffectiveSizeRule {
  Fixed,     // H given directly (the point driver)
  SquareRoot,// H = sqrt(cell area), the paper's simple choice
  Oriented,  // H = cell area / length of the crack line through the cell centre (Fig. 2)
};
// The scene spelling (`effective_size: sqrt | oriented`).
constexpr const char* toString(EffectiveSizeRule r) {
  return r == EffectiveSizeRule::SquareRoot ? "sqrt" : (r == EffectiveSizeRule::Oriented ? "oriented" : "fixed");
}

struct EffectiveSize {
  EffectiveSizeRule rule = EffectiveSizeRule::Fixed;
  double value = 0.0;       // H for Fixed (mm)
  double cellWidth = 0.0;   // cell size in x (mm), for SquareRoot and Oriented
  double cellHeight = 0.0;  // cell size in y (mm)

  static EffectiveSize fixed(double h) { return {EffectiveSizeRule::Fixed, h, 0.0, 0.0}; }

  // The smallest H over all crack directions.
  double smallest() const {
    switch (rule) {
      case EffectiveSizeRule::Fixed: return value;
      case EffectiveSizeRule::SquareRoot: return std::sqrt(cellWidth * cellHeight);
      case EffectiveSizeRule::Oriented: return cellWidth * cellHeight / std::hypot(cellWidth, cellHeight);  // diagonal chord
    }
    return value;
  }

  // H for a crack with unit normal n.
  double operator()(const Vec2& n) const {
    switch (rule) {
      case EffectiveSizeRule::Fixed: return value;
      case EffectiveSizeRule::SquareRoot: return std::sqrt(cellWidth * cellHeight);
      case EffectiveSizeRule::Oriented: {
        // crack line direction t = (-n_y, n_x); its chord through the centre of a w x h cell
        const double tx = std::abs(n[1]), ty = std::abs(n[0]);
        const double chord = std::min(tx > 0.0 ? cellWidth / tx : INFINITY, ty > 0.0 ? cellHeight / ty : INFINITY);
        return cellWidth * cellHeight / chord;
      }
    }
    return value;
  }
};

}  // namespace ecm
