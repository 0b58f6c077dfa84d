// The kinematics of a band of crossed cells (docs/model.md, "Crack paths").
#include "mpm/setup/band_kinematics.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace ecm::mpm {

namespace {
Vec2 leftNormal(const Vec2& a, const Vec2& b) {
  const Vec2 d = (b - a).normalized();
  return {-d[1], d[0]};
}
}  // namespace

bool onLeftOf(const std::vector<Vec2>& path, const Vec2& x) {
  // The segments of nonzero length (a tip that has just become a vertex repeats a point).
  std::vector<std::size_t> from;
  for (std::size_t k = 0; k + 1 < path.size(); ++k)
    if (path[k] != path[k + 1]) from.push_back(k);
  if (from.empty()) return false;
  double best = std::numeric_limits<double>::infinity();
  std::size_t at = 0;
  double along = 0.0;
  for (std::size_t s = 0; s < from.size(); ++s) {
    const Vec2 &a = path[from[s]], &b = path[from[s] + 1];
    const Vec2 d = b - a;
    // The path runs on before its first point and past its last, along its end segments.
    const double first = s == 0 ? -std::numeric_limits<double>::infinity() : 0.0;
    const double last = s + 1 == from.size() ? std::numeric_limits<double>::infinity() : 1.0;
    const double t = std::clamp((x - a).dot(d) / d.squaredNorm(), first, last);
    const double distance = (x - (a + t * d)).squaredNorm();
    if (distance < best) best = distance, at = s, along = t;
  }
  const Vec2 &a = path[from[at]], &b = path[from[at] + 1];
  Vec2 n = leftNormal(a, b);
  if (along <= 0.0 && at > 0) n += leftNormal(path[from[at - 1]], path[from[at - 1] + 1]);
  if (along >= 1.0 && at + 1 < from.size()) n += leftNormal(path[from[at + 1]], path[from[at + 1] + 1]);
  return (x - (a + along * (b - a))).dot(n) >= 0.0;
}

NodeSides nodeSides(const std::vector<Vec2>& path, const Vec2& lo, const Vec2& cellSize) {
  NodeSides s = 0;
  for (int k = 0; k < 4; ++k)
    if (onLeftOf(path, lo + Vec2((k & 1) * cellSize[0], (k >> 1) * cellSize[1]))) s |= static_cast<NodeSides>(1u << k);
  return s;
}

Vec2 sideGradient(NodeSides s, const Vec2& local, const Vec2& cellSize) {
  const double x = local[0], y = local[1];
  // d/dx and d/dy of the bilinear shape functions of nodes 0-3 (lower left, lower right, upper
  // left, upper right), in the cell's unit coordinates.
  const std::array<Vec2, 4> g{Vec2(-(1.0 - y), -(1.0 - x)), Vec2(1.0 - y, -x), Vec2(-y, 1.0 - x), Vec2(y, x)};
  Vec2 sum = Vec2::Zero();
  for (int k = 0; k < 4; ++k)
    if (s & (1u << k)) sum += g[static_cast<std::size_t>(k)];
  return {sum[0] / cellSize[0], sum[1] / cellSize[1]};
}

double sideGradientIntegral(NodeSides s, const Vec2& cellSize, int pointsPerCell, double leastGradient) {
  // The k x k points a cell is seeded with (mpm/setup/seeding.hpp): at the centres of its k x k
  // sub-cells, each of weight 1 / k^2.
  const double k = pointsPerCell, least = leastGradient / std::min(cellSize[0], cellSize[1]);
  double sum = 0.0;
  for (int i = 0; i < pointsPerCell; ++i)
    for (int j = 0; j < pointsPerCell; ++j) {
      const double g = sideGradient(s, Vec2((i + 0.5) / k, (j + 0.5) / k), cellSize).norm();
      if (g >= least) sum += g;
    }
  return sum / (k * k) * cellSize[0] * cellSize[1];
}

}  // namespace ecm::mpm
