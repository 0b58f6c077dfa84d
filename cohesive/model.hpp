#pragma once
// A half model by symmetry: a plane-stress Q4 mesh whose symmetry line carries the crack path.
// Ligament nodes on it are free normal to it and held by the cohesive interface (the opening is
// twice the node's normal displacement: the other half mirrors it); other nodes on it are held
// normal to it. The interface acts at the ligament nodes (nodal, Newton-Cotes/Lobatto
// integration: each node's tributary length times the thickness), which keeps the tractions
// free of the oscillations a Gauss-integrated stiff interface shows (docs/cohesive.md).
// Unknowns are equations: a node's dof is fixed (-1), its own equation, or one shared by a tied
// group (a rigid loading box or edge, moved together).
#include <Eigen/Core>
#include <Eigen/SparseCore>

#include <string>
#include <vector>

#include "cohesive/structured_mesh.hpp"

namespace ecm::cohesive {

struct ElasticBulk {
  double youngsModulus = 0.0;  // E (MPa)
  double poissonRatio = 0.0;   // nu
  double thickness = 0.0;      // b (mm)
};

struct InterfaceNode {
  int node = -1;
  int equation = -1;      // the node's normal dof
  double sign = 1.0;      // opening = 2 sign u_n
  double area = 0.0;      // tributary length x thickness (mm^2)
  double position = 0.0;  // coordinate along the ligament (mm)
};

struct HalfModel {
  StructuredMesh mesh;
  ElasticBulk bulk;
  std::vector<int> dofEquation;  // 2 node + component -> equation, -1 fixed
  int equations = 0;
  std::vector<InterfaceNode> interface;
  Eigen::VectorXd loadPattern;  // f_ref: the half model's load is lambda f_ref
  Eigen::VectorXd control;      // c: the controlled quantity (full specimen) is c . u
  double loadScale = 1.0;       // the full specimen's load P = loadScale lambda
  double loadDisplacementScale = 1.0;  // its load-point displacement = loadDisplacementScale f_ref . u
  double ligamentArea = 0.0;    // full crack area (mm^2)
  std::string controlName;      // "cmod", "delta"
  std::string ligamentAxis;     // the coordinate along the ligament, "x" or "y"
};

// The bulk stiffness (no interface) in equation space.
Eigen::SparseMatrix<double> bulkStiffness(const HalfModel& m);
// A node's displacement from the equation-space vector.
Eigen::Vector2d nodeDisplacement(const HalfModel& m, const Eigen::VectorXd& u, int node);

// Grégoire et al. (2013) notched beam in three-point bending, left half (x from 0 to mid-span).
struct BeamGeometry {
  double depth = 50.0, length = 175.0, span = 125.0;
  double notchWidth = 2.5, notchDepth = 25.0;
  double cmodGauge = 20.0;  // CMOD = u_x(mid + gauge/2, 0) - u_x(mid - gauge/2, 0)
  bool supportBox = false, loadBox = false;
  double boxWidth = 2.5;    // the boxes: nodes within boxWidth/2 of the support / mid-span
};
HalfModel beamModel(const BeamGeometry& g, const ElasticBulk& bulk, double cellSize);

// Nooru-Mohamed's double-edge-notched panel in pure tension, upper half (y from mid-height up);
// the top edge moved uniformly in y (rotation held); control delta = top minus bottom.
struct PanelGeometry {
  double width = 200.0, height = 200.0;
  double notchDepth = 25.0, notchWidth = 5.0;
  bool topHeldInX = false;  // else free in x (one ligament node at mid-width held in x)
};
HalfModel panelTensionModel(const PanelGeometry& g, const ElasticBulk& bulk, double cellSize);

// A bar in uniaxial tension with the interface across its middle, right half (x from 0 to L/2),
// the end x = L/2 moved uniformly; control delta = elongation of the whole bar. One element
// through the height when cellSize >= height.
struct BarGeometry {
  double length = 50.0, height = 10.0;
};
HalfModel barTensionModel(const BarGeometry& g, const ElasticBulk& bulk, double cellSize);

}  // namespace ecm::cohesive
