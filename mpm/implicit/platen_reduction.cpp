// The platens' change of unknowns (mpm/implicit/platen_reduction.hpp).
#include "mpm/implicit/platen_reduction.hpp"

namespace ecm::mpm {

PlatenReduction platenReduction(const Scene& scene, const std::vector<PlatenState>& platens, const DofMap& dofs,
                                const std::vector<std::array<bool, 3>>& prescribed) {
  const Grid& grid = scene.grid;
  const int n = dofs.unknowns();
  // The platen of each node (-1: none).
  std::vector<int> owner(static_cast<std::size_t>(grid.nodeCount()), -1);
  for (std::size_t p = 0; p < platens.size(); ++p)
    for (const std::int32_t node : platens[p].nodes) owner[static_cast<std::size_t>(node)] = static_cast<int>(p);
  // Columns: the unknowns of no platen in their order, then each platen's unprescribed degrees of freedom.
  PlatenReduction r;
  std::vector<int> plainColumn(static_cast<std::size_t>(n), -1);
  int m = 0;
  for (int u = 0; u < n; ++u)
    if (owner[static_cast<std::size_t>(dofs.component[static_cast<std::size_t>(u)] / 2)] < 0) plainColumn[static_cast<std::size_t>(u)] = m++;
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
  r.t.resize(n, m);
  r.t.setFromTriplets(triplets.begin(), triplets.end());
  r.t.makeCompressed();
  r.tt = r.t.transpose();
  return r;
}

Eigen::SparseMatrix<double> reduceTangent(const PlatenReduction& r, const Eigen::SparseMatrix<double>& k) {
  Eigen::SparseMatrix<double> kt = k * r.t;
  Eigen::SparseMatrix<double> reduced = r.tt * kt;
  reduced.makeCompressed();
  return reduced;
}

}  // namespace ecm::mpm
