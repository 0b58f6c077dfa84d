// The step's change of unknowns: platens and tied nodes (mpm/implicit/platen_and_tie_unknowns.hpp).
#include "mpm/implicit/platen_and_tie_unknowns.hpp"

namespace ecm::mpm {

UnknownReduction unknownReduction(const Scene& scene, const std::vector<PlatenState>& platens, const DofMap& dofs,
                                  const std::vector<std::array<bool, 3>>& prescribed, const std::vector<NodeTie>& ties) {
  const Grid& grid = scene.grid;
  const int n = dofs.unknowns();
  // The platen of each node (-1: none).
  std::vector<int> owner(static_cast<std::size_t>(grid.nodeCount()), -1);
  for (std::size_t p = 0; p < platens.size(); ++p)
    for (const std::int32_t node : platens[p].nodes) owner[static_cast<std::size_t>(node)] = static_cast<int>(p);
  std::vector<std::uint8_t> tied(static_cast<std::size_t>(grid.nodeCount()), 0);
  for (const NodeTie& t : ties) tied[static_cast<std::size_t>(t.node)] = 1;
  // Columns: the unknowns of no platen and no tie in their order, then each platen's unprescribed degrees of freedom.
  UnknownReduction r;
  std::vector<int> plainColumn(static_cast<std::size_t>(n), -1);
  int m = 0;
  for (int u = 0; u < n; ++u) {
    const auto node = static_cast<std::size_t>(dofs.component[static_cast<std::size_t>(u)] / 2);
    if (owner[node] < 0 && !tied[node]) plainColumn[static_cast<std::size_t>(u)] = m++;
  }
  r.column.assign(platens.size(), {-1, -1, -1});
  for (std::size_t p = 0; p < platens.size(); ++p)
    for (int d = 0; d < 3; ++d)
      if (!prescribed[p][static_cast<std::size_t>(d)]) r.column[p][static_cast<std::size_t>(d)] = m++;
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(static_cast<std::size_t>(n) + 8);
  for (int u = 0; u < n; ++u) {
    const std::int32_t component = dofs.component[static_cast<std::size_t>(u)];
    const std::int32_t node = component / 2;
    const int p = owner[static_cast<std::size_t>(node)];
    if (tied[static_cast<std::size_t>(node)]) continue;  // below
    if (p < 0) {
      triplets.emplace_back(u, plainColumn[static_cast<std::size_t>(u)], 1.0);
      continue;
    }
    const Eigen::Matrix<double, 2, 3> b = rigidMap(grid.nodePosition(node), platens[static_cast<std::size_t>(p)].reference);
    for (int d = 0; d < 3; ++d) {
      const int column = r.column[static_cast<std::size_t>(p)][static_cast<std::size_t>(d)];
      if (column >= 0 && b(component % 2, d) != 0.0) triplets.emplace_back(u, column, b(component % 2, d));
    }
  }
  // A tied component: its sources' columns (a prescribed source has none: its share is an increment).
  for (const NodeTie& t : ties)
    for (int d = 0; d < 2; ++d) {
      const std::int32_t u = dofs.unknownOf[2 * static_cast<std::size_t>(t.node) + static_cast<std::size_t>(d)];
      if (u < 0) continue;
      for (int k = 0; k < t.sources; ++k) {
        const std::int32_t s = dofs.unknownOf[2 * static_cast<std::size_t>(t.source[static_cast<std::size_t>(k)]) + static_cast<std::size_t>(d)];
        if (s >= 0) triplets.emplace_back(u, plainColumn[static_cast<std::size_t>(s)], t.coefficient[static_cast<std::size_t>(k)]);
      }
    }
  r.t.resize(n, m);
  r.t.setFromTriplets(triplets.begin(), triplets.end());
  r.t.makeCompressed();
  r.tt = r.t.transpose();
  return r;
}

Eigen::SparseMatrix<double> reduceTangent(const UnknownReduction& r, const Eigen::SparseMatrix<double>& k) {
  Eigen::SparseMatrix<double> kt = k * r.t;
  Eigen::SparseMatrix<double> reduced = r.tt * kt;
  reduced.makeCompressed();
  return reduced;
}

std::vector<int> unknownComponents(const DofMap& dofs, const UnknownReduction* r) {
  std::vector<int> xy;
  if (!r) {
    xy.reserve(dofs.component.size());
    for (const std::int32_t c : dofs.component) xy.push_back(c % 2);
    return xy;
  }
  xy.assign(static_cast<std::size_t>(r->reduced()), 0);
  for (int j = 0; j < r->reduced(); ++j) {
    Eigen::SparseMatrix<double>::InnerIterator it(r->t, j);
    if (it) xy[static_cast<std::size_t>(j)] = dofs.component[static_cast<std::size_t>(it.row())] % 2;
  }
  return xy;
}

}  // namespace ecm::mpm
