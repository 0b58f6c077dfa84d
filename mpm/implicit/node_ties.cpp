// Nodes the body barely reaches, tied to their neighbours (mpm/implicit/node_ties.hpp).
#include "mpm/implicit/node_ties.hpp"

#include <cstddef>

namespace ecm::mpm {

namespace {

// One axis's part of a rule: offset 0 keeps the node's own index (coefficient 1); +-1 extrapolates
// from the next two indices on that side, 2 u(i + s) - u(i + 2 s).
struct AxisRule {
  int count;
  std::array<int, 2> offset;
  std::array<double, 2> coefficient;
};

AxisRule axisRule(int s) {
  if (s == 0) return {1, {0, 0}, {1.0, 0.0}};
  return {2, {s, 2 * s}, {2.0, -1.0}};
}

}  // namespace

std::vector<NodeTie> weakNodeTies(int nx, int ny, const std::vector<double>& share, const std::vector<std::uint8_t>& mayTie,
                                  const std::vector<std::uint8_t>& maySource) {
  const auto at = [&](int ix, int iy) { return static_cast<std::size_t>(iy) * static_cast<std::size_t>(nx) + static_cast<std::size_t>(ix); };
  // The rules in order of preference: one axis (-y, +y, -x, +x), then the corners.
  static constexpr std::array<std::array<int, 2>, 8> kRules{{{0, -1}, {0, 1}, {-1, 0}, {1, 0}, {-1, -1}, {-1, 1}, {1, -1}, {1, 1}}};
  std::vector<NodeTie> ties;
  for (int iy = 0; iy < ny; ++iy)
    for (int ix = 0; ix < nx; ++ix) {
      const std::size_t n = at(ix, iy);
      if (!(share[n] > 0.0 && share[n] < kWeakNodeShare) || !mayTie[n]) continue;
      NodeTie best;
      double bestShare = -1.0;
      bool bestIsAxis = false;
      for (std::size_t r = 0; r < kRules.size(); ++r) {
        const bool axis = r < 4;
        if (bestShare >= 0.0 && bestIsAxis && !axis) break;  // a corner rule only where no axis rule serves
        const AxisRule rx = axisRule(kRules[r][0]), ry = axisRule(kRules[r][1]);
        NodeTie tie;
        tie.node = static_cast<std::int32_t>(n);
        double sum = 0.0;
        bool ok = true;
        for (int a = 0; a < ry.count && ok; ++a)
          for (int b = 0; b < rx.count && ok; ++b) {
            const int jx = ix + rx.offset[static_cast<std::size_t>(b)], jy = iy + ry.offset[static_cast<std::size_t>(a)];
            if (jx < 0 || jy < 0 || jx >= nx || jy >= ny) {
              ok = false;
              break;
            }
            const std::size_t m = at(jx, jy);
            if (!(share[m] >= kWeakNodeShare) || !maySource[m]) {
              ok = false;
              break;
            }
            tie.source[static_cast<std::size_t>(tie.sources)] = static_cast<std::int32_t>(m);
            tie.coefficient[static_cast<std::size_t>(tie.sources)] = rx.coefficient[static_cast<std::size_t>(b)] * ry.coefficient[static_cast<std::size_t>(a)];
            ++tie.sources;
            sum += share[m];
          }
        if (ok && sum > bestShare) best = tie, bestShare = sum, bestIsAxis = axis;
      }
      if (bestShare >= 0.0) ties.push_back(best);
    }
  return ties;
}

}  // namespace ecm::mpm
