#pragma once
// The rigid platens in the implicit load step (mpm/scene/platen.hpp, docs/implicit.md): the node
// components of a platen's nodes are unknowns of K like any other, and a change of unknowns
// du = T dq ties them to the platen's degrees of freedom: an unknown of no platen keeps its own
// column of T (1), a node component of platen p gets the row of its rigid map B_k over p's
// unprescribed degrees of freedom. Newton then solves T^T K T dq = T^T r; the platen's prescribed
// degrees of freedom enter as increments of its node components (B_k dq_prescribed), as a held
// or driven node's do.
#include <Eigen/Sparse>

#include <array>
#include <vector>

#include "mpm/implicit/implicit_system.hpp"

namespace ecm::mpm {

struct PlatenReduction {
  Eigen::SparseMatrix<double> t;         // unknowns x reduced unknowns
  Eigen::SparseMatrix<double> tt;        // its transpose
  std::vector<std::array<int, 3>> column;  // per platen and degree of freedom: its reduced unknown (-1: prescribed)
  int reduced() const { return static_cast<int>(t.cols()); }
};

// The change of unknowns of a step's geometry. `prescribed[p][d]`: platen p's degree of freedom d
// is held or driven in this step (its increment known).
PlatenReduction platenReduction(const Scene& scene, const std::vector<PlatenState>& platens, const DofMap& dofs,
                                const std::vector<std::array<bool, 3>>& prescribed);

// v[u] = f(node component of unknown u) over the unknowns, then T^T v when `r` is given.
template <class F>
Eigen::VectorXd onUnknowns(const DofMap& dofs, const PlatenReduction* r, F&& f) {
  const int n = dofs.unknowns();
  Eigen::VectorXd v(n);
  for (int u = 0; u < n; ++u) v[u] = f(dofs.component[static_cast<std::size_t>(u)]);
  if (!r) return v;
  return r->tt * v;
}

// The unknowns' values of a (reduced) solution: x itself, or T x.
inline Eigen::VectorXd toUnknowns(const PlatenReduction* r, const Eigen::VectorXd& x) {
  if (!r) return x;
  return r->t * x;
}

// T^T K T (K over the unknowns).
Eigen::SparseMatrix<double> reduceTangent(const PlatenReduction& r, const Eigen::SparseMatrix<double>& k);

}  // namespace ecm::mpm
