#pragma once
// A structured mesh of 4-node quadrilaterals on a tensor grid of x and y lines, with rectangular
// cut-outs (notches) removed. The grid lines: between consecutive lines that must be present,
// equal cells no longer than the target size.
#include <Eigen/Core>

#include <array>
#include <vector>

namespace ecm::cohesive {

struct Rectangle {
  double xMin, yMin, xMax, yMax;
};

// Lines from lo to hi holding every entry of `required` (those outside [lo, hi] are ignored),
// each gap between required lines cut into ceil(gap / cellSize) equal cells.
std::vector<double> gridLines(double lo, double hi, std::vector<double> required, double cellSize);

struct StructuredMesh {
  std::vector<double> xLines, yLines;
  std::vector<Eigen::Vector2d> nodes;
  std::vector<std::array<int, 4>> elements;  // counter-clockwise, from the lower left
  std::vector<int> nodeOfGridPoint;           // (i, j) -> node, -1 where no element touches it
  // The node at (x, y) within 1e-9 of a grid point, or -1.
  int nodeAt(double x, double y) const;
  // Every node within the closed box.
  std::vector<int> nodesIn(const Rectangle& box) const;
};

// Cells whose centre lies inside a cut-out are removed; so are nodes no cell touches.
StructuredMesh structuredMesh(const std::vector<double>& xLines, const std::vector<double>& yLines,
                              const std::vector<Rectangle>& cutOuts);

// The stiffness of a plane-stress bilinear quadrilateral (2x2 Gauss), dofs (u_x, u_y) per
// corner in the element's node order.
Eigen::Matrix<double, 8, 8> planeStressQ4Stiffness(const std::array<Eigen::Vector2d, 4>& corners, double youngsModulus,
                                                   double poissonRatio, double thickness);

}  // namespace ecm::cohesive
