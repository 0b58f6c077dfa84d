#pragma once
// The implicit load step's change of unknowns du = T dq (docs/implicit.md): the node components
// of the step's DofMap stay the unknowns of K, and T ties some of them to fewer degrees of freedom.
// - A rigid platen (mpm/scene/platen.hpp): a node component of platen p gets the row of its rigid
//   map B_k over p's unprescribed degrees of freedom; the platen's prescribed degrees of freedom
//   enter as increments of its node components (B_k dq_prescribed), as a held or driven node's do.
// - A node the body barely reaches (mpm/implicit/node_ties.hpp): its row is the sum of its
//   sources' rows times their coefficients; a prescribed source's share enters as an increment
//   of the tied component (applyTies on du and on the control's direction).
// Every other unknown keeps its own column of T (1). Newton then solves T^T K T dq = T^T r.
#include <Eigen/Sparse>

#include <array>
#include <vector>

#include "mpm/implicit/implicit_system.hpp"
#include "mpm/implicit/node_ties.hpp"

namespace ecm::mpm {

struct UnknownReduction {
  Eigen::SparseMatrix<double> t;         // unknowns x reduced unknowns
  Eigen::SparseMatrix<double> tt;        // its transpose
  std::vector<std::array<int, 3>> column;  // per platen and degree of freedom: its reduced unknown (-1: prescribed)
  int reduced() const { return static_cast<int>(t.cols()); }
};

// The change of unknowns of a step's geometry. `prescribed[p][d]`: platen p's degree of freedom d
// is held or driven in this step (its increment known). `ties`: weakNodeTies of the step, whose
// sources are unknowns of no platen or prescribed components.
UnknownReduction unknownReduction(const Scene& scene, const std::vector<PlatenState>& platens, const DofMap& dofs,
                                  const std::vector<std::array<bool, 3>>& prescribed, const std::vector<NodeTie>& ties);

// v[u] = f(node component of unknown u) over the unknowns, then T^T v when `r` is given.
template <class F>
Eigen::VectorXd onUnknowns(const DofMap& dofs, const UnknownReduction* r, F&& f) {
  const int n = dofs.unknowns();
  Eigen::VectorXd v(n);
  for (int u = 0; u < n; ++u) v[u] = f(dofs.component[static_cast<std::size_t>(u)]);
  if (!r) return v;
  return r->tt * v;
}

// The unknowns' values of a (reduced) solution: x itself, or T x.
inline Eigen::VectorXd toUnknowns(const UnknownReduction* r, const Eigen::VectorXd& x) {
  if (!r) return x;
  return r->t * x;
}

// Each (reduced) unknown's displacement component, 0 x or 1 y: that of the first node component
// its column of T moves (a platen's rotation counts as x). For the AMG solver.
std::vector<int> unknownComponents(const DofMap& dofs, const UnknownReduction* r);

// T^T K T (K over the unknowns).
Eigen::SparseMatrix<double> reduceTangent(const UnknownReduction& r, const Eigen::SparseMatrix<double>& k);

}  // namespace ecm::mpm
