#include "cohesive/structured_mesh.hpp"

#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace ecm::cohesive {

std::vector<double> gridLines(double lo, double hi, std::vector<double> required, double cellSize) {
  if (!(hi > lo) || !(cellSize > 0.0)) throw std::invalid_argument("gridLines: need hi > lo and a positive cell size");
  const double eps = 1e-9 * (hi - lo);
  std::erase_if(required, [&](double v) { return v <= lo + eps || v >= hi - eps; });
  required.push_back(lo);
  required.push_back(hi);
  std::sort(required.begin(), required.end());
  required.erase(std::unique(required.begin(), required.end(), [&](double a, double b) { return std::abs(a - b) <= eps; }),
                 required.end());
  std::vector<double> lines{required.front()};
  for (std::size_t k = 1; k < required.size(); ++k) {
    const double a = required[k - 1], b = required[k];
    const int cells = std::max(1, static_cast<int>(std::ceil((b - a) / cellSize - 1e-9)));
    for (int c = 1; c < cells; ++c) lines.push_back(a + (b - a) * c / cells);
    lines.push_back(b);
  }
  return lines;
}

StructuredMesh structuredMesh(const std::vector<double>& xLines, const std::vector<double>& yLines,
                              const std::vector<Rectangle>& cutOuts) {
  StructuredMesh m;
  m.xLines = xLines;
  m.yLines = yLines;
  const int nx = static_cast<int>(xLines.size()), ny = static_cast<int>(yLines.size());
  m.nodeOfGridPoint.assign(static_cast<std::size_t>(nx) * ny, -1);
  const auto grid = [&](int i, int j) -> int& { return m.nodeOfGridPoint[static_cast<std::size_t>(j) * nx + i]; };
  std::vector<std::array<int, 2>> cells;
  for (int j = 0; j + 1 < ny; ++j)
    for (int i = 0; i + 1 < nx; ++i) {
      const double cx = 0.5 * (xLines[i] + xLines[i + 1]), cy = 0.5 * (yLines[j] + yLines[j + 1]);
      const bool cut = std::any_of(cutOuts.begin(), cutOuts.end(), [&](const Rectangle& r) {
        return cx > r.xMin && cx < r.xMax && cy > r.yMin && cy < r.yMax;
      });
      if (cut) continue;
      cells.push_back({i, j});
      grid(i, j) = grid(i + 1, j) = grid(i + 1, j + 1) = grid(i, j + 1) = 0;  // touched
    }
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i)
      if (grid(i, j) == 0) {
        grid(i, j) = static_cast<int>(m.nodes.size());
        m.nodes.emplace_back(xLines[i], yLines[j]);
      }
  for (const auto& [i, j] : cells) m.elements.push_back({grid(i, j), grid(i + 1, j), grid(i + 1, j + 1), grid(i, j + 1)});
  return m;
}

namespace {
int lineIndex(const std::vector<double>& lines, double v) {
  const double eps = 1e-9 * std::max(1.0, std::abs(lines.back() - lines.front()));
  const auto it = std::lower_bound(lines.begin(), lines.end(), v - eps);
  if (it == lines.end() || std::abs(*it - v) > eps) return -1;
  return static_cast<int>(it - lines.begin());
}
}  // namespace

int StructuredMesh::nodeAt(double x, double y) const {
  const int i = lineIndex(xLines, x), j = lineIndex(yLines, y);
  if (i < 0 || j < 0) return -1;
  return nodeOfGridPoint[static_cast<std::size_t>(j) * xLines.size() + i];
}

std::vector<int> StructuredMesh::nodesIn(const Rectangle& box) const {
  const double eps = 1e-9;
  std::vector<int> found;
  for (int n = 0; n < static_cast<int>(nodes.size()); ++n) {
    const Eigen::Vector2d& p = nodes[n];
    if (p.x() >= box.xMin - eps && p.x() <= box.xMax + eps && p.y() >= box.yMin - eps && p.y() <= box.yMax + eps) found.push_back(n);
  }
  return found;
}

Eigen::Matrix<double, 8, 8> planeStressQ4Stiffness(const std::array<Eigen::Vector2d, 4>& corners, double e, double nu,
                                                   double thickness) {
  Eigen::Matrix3d d;
  d << 1.0, nu, 0.0, nu, 1.0, 0.0, 0.0, 0.0, 0.5 * (1.0 - nu);
  d *= e / (1.0 - nu * nu);
  const double g = 1.0 / std::sqrt(3.0);
  const double xi[4] = {-1, 1, 1, -1}, eta[4] = {-1, -1, 1, 1};
  Eigen::Matrix<double, 8, 8> k = Eigen::Matrix<double, 8, 8>::Zero();
  for (int q = 0; q < 4; ++q) {
    const double s = xi[q] * g, t = eta[q] * g;
    Eigen::Matrix<double, 2, 4> dn;  // d N / d (xi, eta)
    for (int a = 0; a < 4; ++a) {
      dn(0, a) = 0.25 * xi[a] * (1.0 + eta[a] * t);
      dn(1, a) = 0.25 * eta[a] * (1.0 + xi[a] * s);
    }
    Eigen::Matrix2d jac = Eigen::Matrix2d::Zero();
    for (int a = 0; a < 4; ++a) jac += dn.col(a) * corners[a].transpose();
    const double det = jac.determinant();
    const Eigen::Matrix<double, 2, 4> dx = jac.inverse() * dn;
    Eigen::Matrix<double, 3, 8> b = Eigen::Matrix<double, 3, 8>::Zero();
    for (int a = 0; a < 4; ++a) {
      b(0, 2 * a) = dx(0, a);
      b(1, 2 * a + 1) = dx(1, a);
      b(2, 2 * a) = dx(1, a);
      b(2, 2 * a + 1) = dx(0, a);
    }
    k += b.transpose() * d * b * (det * thickness);
  }
  return k;
}

}  // namespace ecm::cohesive
