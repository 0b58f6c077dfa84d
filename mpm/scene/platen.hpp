#pragma once
// A rigid loading platen (`platens:` of a scene; docs/inputs.md, docs/validation.md): grid nodes
// picked by one or more boxes (the nodes of the specimen's edge glued to the steel) that move as
// one rigid body. Its three degrees of freedom are about a reference point r: the translation
// (u_x, u_y) of r and the rotation theta, so that a node at x moves by
//   u(x) = (u_x - theta (x_y - r_y), u_y + theta (x_x - r_x))      (small rotations)
// Each degree of freedom is held, driven by a displacement history (mm, rad), driven by a force
// history (N, N mm: the force the rig puts on the specimen) or free. What the platen puts on the
// specimen (its force and moment about r) and where it is go into history.csv. A steel frame
// that carries two edges of a specimen (the L-frames of the double-edge-notched test) is one
// platen with two boxes.
#include <array>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "mpm/scene/geometry.hpp"
#include "mpm/scene/time_function.hpp"

namespace ecm::mpm {

enum class PlatenDrive {
  Free,          // no force: the platen follows the specimen
  Held,          // does not move
  Displacement,  // u = history(t) (mm; rad for the rotation)
  Force,         // the rig's force on the specimen = history(t) (N; N mm for the rotation)
};

struct PlatenDof {
  PlatenDrive drive = PlatenDrive::Held;
  TimeFunction history;    // for Displacement and Force
  // Displacement only: free (no force) before this time (s), then driven by the history's
  // increments from where it is: a rig that first lets the specimen go and then takes hold of it
  // (the double-edge-notched test's axial actuator at P = 0 while the shear force rises).
  double freeUntil = 0.0;

  // Whether a displacement-driven degree of freedom is driven over a step that starts at `t`.
  bool drivenAt(double t) const { return drive == PlatenDrive::Displacement && t >= freeUntil; }
};

// The degrees of freedom of a platen, in this order.
enum PlatenAxis { kPlatenX = 0, kPlatenY = 1, kPlatenRotation = 2 };

struct Platen {
  std::string name;
  std::vector<Box> boxes;          // its nodes: every grid node inside one of them
  std::optional<Vec2> reference;   // mm: the point its rotation and moment refer to (default: the mean of its nodes)
  std::array<PlatenDof, 3> dof;    // x, y, rotation
};

// How a node at `x` moves with the platen's degrees of freedom (u_x, u_y, theta) about `reference`:
// u(x) = B q with B = [1 0 -(x_y - r_y); 0 1 (x_x - r_x)] (small rotations).
inline Eigen::Matrix<double, 2, 3> rigidMap(const Vec2& x, const Vec2& reference) {
  Eigen::Matrix<double, 2, 3> b;
  b << 1.0, 0.0, -(x[1] - reference[1]), 0.0, 1.0, x[0] - reference[0];
  return b;
}

// Solves A q = b for A = sum_k w_k B_k^T B_k (weights w_k > 0): the rigid motion that fits nodal
// values, or the nodal share of a platen's force. With all of the weight on one point (no rotation
// to find: A is singular) the rotation is 0 and the translation the weighted mean.
inline Eigen::Vector3d solveRigid(const Eigen::Matrix3d& a, const Eigen::Vector3d& b) {
  if (!(a(0, 0) > 0.0)) return Eigen::Vector3d::Zero();
  const double spin = a(2, 2) - (a(0, 2) * a(0, 2) + a(1, 2) * a(1, 2)) / a(0, 0);  // inertia about the centroid
  if (spin > 1e-12 * a(2, 2)) return a.inverse() * b;
  return Eigen::Vector3d(b[0] / a(0, 0), b[1] / a(1, 1), 0.0);
}

// A platen whose degree of freedom `d` is driven by a displacement (its force is the structure's load).
inline bool displacementDriven(const Platen& p, int d) { return p.dof[static_cast<std::size_t>(d)].drive == PlatenDrive::Displacement; }

}  // namespace ecm::mpm
