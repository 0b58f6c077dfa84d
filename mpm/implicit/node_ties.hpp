#pragma once
// Nodes the body barely reaches, tied to their neighbours (docs/implicit.md, "Nodes the body
// barely reaches"). A uGIMP particle whose domain pokes a few hundredths of a cell past a node
// line reaches the next row of nodes with a tiny weight. Left free, such a node's equation
// sum_p V_p grad S_p . sigma_p = 0 is carried by those particles alone, so it forces their stress
// to zero: the row next to a driven edge unloads and the row below carries twice the stress. A
// node whose share of the body is below `kWeakNodeShare` of a cell is therefore no unknown of its
// own: its displacement increment is the linear extrapolation of two rows of inner nodes
// (u_weak = 2 u_1 - u_2 along one axis, the tensor product of two such rules at a corner), which
// keeps every linear displacement field exact (the patch test).
#include <array>
#include <cstdint>
#include <vector>

namespace ecm::mpm {

// A node's share of the body below which it is tied: 10 % of a cell (an inner node carries 1, a
// node on a straight edge 1/2, on a convex corner 1/4).
inline constexpr double kWeakNodeShare = 0.1;

// u(node) = sum_k coefficient[k] u(source[k]), both components alike.
struct NodeTie {
  std::int32_t node = -1;
  int sources = 0;
  std::array<std::int32_t, 4> source{};
  std::array<double, 4> coefficient{};
  bool operator==(const NodeTie&) const = default;
};

// The ties of a grid of nx x ny nodes (node = iy nx + ix). `share[n]`: the body's volume the node
// carries, sum_p S_np V_p, over a cell's volume (0: not reached). A node is tied when
// 0 < share < kWeakNodeShare and `mayTie[n]`; its sources must have share >= kWeakNodeShare and
// `maySource`. Among the rules that qualify, one axis is preferred to a corner, then the largest
// summed share of the sources, then the first in the order -y, +y, -x, +x (corners: the signs of
// x then y). A weak node no rule serves stays free.
std::vector<NodeTie> weakNodeTies(int nx, int ny, const std::vector<double>& share, const std::vector<std::uint8_t>& mayTie,
                                  const std::vector<std::uint8_t>& maySource);

// v[tied component] = sum_k coefficient_k v[source component] for every tie (v per node component).
template <class Vector>
void applyTies(const std::vector<NodeTie>& ties, Vector& v) {
  for (const NodeTie& t : ties)
    for (int d = 0; d < 2; ++d) {
      double sum = 0.0;
      for (int k = 0; k < t.sources; ++k) sum += t.coefficient[static_cast<std::size_t>(k)] * v[2 * t.source[static_cast<std::size_t>(k)] + d];
      v[2 * t.node + d] = sum;
    }
}

// The transpose: what a tied node holds (a force) moves to its sources, v[tied] becomes 0.
template <class Vector>
void transferTies(const std::vector<NodeTie>& ties, Vector& v) {
  for (const NodeTie& t : ties)
    for (int d = 0; d < 2; ++d) {
      const double held = v[2 * t.node + d];
      for (int k = 0; k < t.sources; ++k) v[2 * t.source[static_cast<std::size_t>(k)] + d] += t.coefficient[static_cast<std::size_t>(k)] * held;
      v[2 * t.node + d] = 0.0;
    }
}

}  // namespace ecm::mpm
