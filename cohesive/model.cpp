#include "cohesive/model.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace ecm::cohesive {

namespace {

constexpr double kEps = 1e-9;

// Numbers the free dofs; `ties` are groups of dofs (2 node + component) sharing one equation.
void numberEquations(HalfModel& m, const std::vector<bool>& fixed, const std::vector<std::vector<int>>& ties) {
  const std::size_t dofs = 2 * m.mesh.nodes.size();
  m.dofEquation.assign(dofs, -2);
  int next = 0;
  for (const auto& group : ties) {
    for (int d : group) m.dofEquation[d] = next;
    ++next;
  }
  for (std::size_t d = 0; d < dofs; ++d) {
    if (fixed[d]) m.dofEquation[d] = -1;
    else if (m.dofEquation[d] == -2) m.dofEquation[d] = next++;
  }
  m.equations = next;
  m.loadPattern = Eigen::VectorXd::Zero(next);
  m.control = Eigen::VectorXd::Zero(next);
}

// Interface nodes on the symmetry line (component `normal` = c at value `at`) within [lo, hi]
// of the other coordinate; the rest of the line's nodes are fixed normal to it.
void symmetryLine(HalfModel& m, std::vector<bool>& fixed, int normal, double at, double lo, double hi, double sign) {
  const int along = 1 - normal;
  std::vector<int> ligament;
  for (int n = 0; n < static_cast<int>(m.mesh.nodes.size()); ++n) {
    const Eigen::Vector2d& p = m.mesh.nodes[n];
    if (std::abs(p[normal] - at) > kEps) continue;
    if (p[along] >= lo - kEps && p[along] <= hi + kEps) ligament.push_back(n);
    else fixed[2 * n + normal] = true;
  }
  std::sort(ligament.begin(), ligament.end(), [&](int a, int b) { return m.mesh.nodes[a][along] < m.mesh.nodes[b][along]; });
  if (ligament.size() < 2) throw std::invalid_argument("the ligament holds fewer than two nodes");
  m.interface.clear();
  for (std::size_t k = 0; k < ligament.size(); ++k) {
    const double s = m.mesh.nodes[ligament[k]][along];
    const double before = k > 0 ? s - m.mesh.nodes[ligament[k - 1]][along] : 0.0;
    const double after = k + 1 < ligament.size() ? m.mesh.nodes[ligament[k + 1]][along] - s : 0.0;
    m.interface.push_back({ligament[k], -1, sign, 0.5 * (before + after) * m.bulk.thickness, s});
  }
  m.ligamentAxis.assign(1, along == 0 ? 'x' : 'y');  // (a char: GCC 12 warns falsely, -Wrestrict, on a const char*)
}

void finishInterface(HalfModel& m, int normal) {
  m.ligamentArea = 0.0;
  for (InterfaceNode& i : m.interface) {
    i.equation = m.dofEquation[2 * i.node + normal];
    m.ligamentArea += i.area;
  }
}

int requireNode(const StructuredMesh& mesh, double x, double y, const char* what) {
  const int n = mesh.nodeAt(x, y);
  if (n < 0) throw std::invalid_argument(std::string("no mesh node at the ") + what);
  return n;
}

}  // namespace

Eigen::SparseMatrix<double> bulkStiffness(const HalfModel& m) {
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(m.mesh.elements.size() * 64);
  for (const auto& e : m.mesh.elements) {
    std::array<Eigen::Vector2d, 4> corners;
    for (int a = 0; a < 4; ++a) corners[a] = m.mesh.nodes[e[a]];
    const Eigen::Matrix<double, 8, 8> k = planeStressQ4Stiffness(corners, m.bulk.youngsModulus, m.bulk.poissonRatio, m.bulk.thickness);
    for (int a = 0; a < 8; ++a) {
      const int ra = m.dofEquation[2 * e[a / 2] + a % 2];
      if (ra < 0) continue;
      for (int b = 0; b < 8; ++b) {
        const int rb = m.dofEquation[2 * e[b / 2] + b % 2];
        if (rb >= 0) t.emplace_back(ra, rb, k(a, b));
      }
    }
  }
  Eigen::SparseMatrix<double> k(m.equations, m.equations);
  k.setFromTriplets(t.begin(), t.end());
  return k;
}

Eigen::Vector2d nodeDisplacement(const HalfModel& m, const Eigen::VectorXd& u, int node) {
  Eigen::Vector2d d;
  for (int c = 0; c < 2; ++c) {
    const int e = m.dofEquation[2 * node + c];
    d[c] = e >= 0 ? u[e] : 0.0;
  }
  return d;
}

HalfModel beamModel(const BeamGeometry& g, const ElasticBulk& bulk, double cellSize) {
  HalfModel m;
  m.bulk = bulk;
  const double mid = 0.5 * g.length, support = mid - 0.5 * g.span, hw = 0.5 * g.boxWidth;
  const double gaugeX = mid - 0.5 * g.cmodGauge, notchFace = mid - 0.5 * g.notchWidth;
  std::vector<double> xs{support, gaugeX, notchFace};
  if (g.supportBox) { xs.push_back(support - hw); xs.push_back(support + hw); }
  if (g.loadBox) xs.push_back(mid - hw);
  m.mesh = structuredMesh(gridLines(0.0, mid, xs, cellSize), gridLines(0.0, g.depth, {g.notchDepth}, cellSize),
                          {{notchFace, -1.0, mid + 1.0, g.notchDepth}});
  const std::size_t dofs = 2 * m.mesh.nodes.size();
  std::vector<bool> fixed(dofs, false);
  symmetryLine(m, fixed, 0, mid, g.notchDepth, g.depth, -1.0);  // the left half opens towards -x
  // Supports: u_y = 0 at the node (25, 0) or at every bottom node within the box.
  std::vector<int> supports = g.supportBox ? m.mesh.nodesIn({support - hw, 0.0, support + hw, 0.0})
                                           : std::vector<int>{requireNode(m.mesh, support, 0.0, "support")};
  for (int n : supports) fixed[2 * n + 1] = true;
  // The load: -y on the mid-span top node, or on the top nodes within the box moved together.
  std::vector<int> loaded = g.loadBox ? m.mesh.nodesIn({mid - hw, g.depth, mid, g.depth})
                                      : std::vector<int>{requireNode(m.mesh, mid, g.depth, "load point")};
  std::vector<int> tie;
  for (int n : loaded) tie.push_back(2 * n + 1);
  numberEquations(m, fixed, {tie});
  finishInterface(m, 0);
  m.loadPattern[0] = -1.0;  // the tie is equation 0
  m.loadScale = 2.0;        // the half model carries half the load
  m.loadDisplacementScale = 1.0;
  const int gauge = requireNode(m.mesh, gaugeX, 0.0, "CMOD gauge");
  m.control[m.dofEquation[2 * gauge]] = -2.0;  // CMOD = u_x(mirror) - u_x = -2 u_x
  m.controlName = "cmod";
  return m;
}

HalfModel panelTensionModel(const PanelGeometry& g, const ElasticBulk& bulk, double cellSize) {
  HalfModel m;
  m.bulk = bulk;
  const double midY = 0.5 * g.height, midX = 0.5 * g.width;
  const double notchTop = midY + 0.5 * g.notchWidth;
  m.mesh = structuredMesh(gridLines(0.0, g.width, {g.notchDepth, g.width - g.notchDepth, midX}, cellSize),
                          gridLines(midY, g.height, {notchTop}, cellSize),
                          {{-1.0, midY - 1.0, g.notchDepth, notchTop}, {g.width - g.notchDepth, midY - 1.0, g.width + 1.0, notchTop}});
  std::vector<bool> fixed(2 * m.mesh.nodes.size(), false);
  symmetryLine(m, fixed, 1, midY, g.notchDepth, g.width - g.notchDepth, 1.0);
  const std::vector<int> top = m.mesh.nodesIn({-1.0, g.height, g.width + 1.0, g.height});
  std::vector<int> tie;
  for (int n : top) {
    tie.push_back(2 * n + 1);
    if (g.topHeldInX) fixed[2 * n] = true;
  }
  if (!g.topHeldInX) fixed[2 * requireNode(m.mesh, midX, midY, "ligament's middle")] = true;  // x rigid-body mode
  numberEquations(m, fixed, {tie});
  finishInterface(m, 1);
  m.loadPattern[0] = 1.0;
  m.loadScale = 1.0;               // both halves carry the whole load
  m.loadDisplacementScale = 2.0;   // delta = top - bottom = 2 u_top
  m.control[0] = 2.0;
  m.controlName = "delta";
  return m;
}

HalfModel barTensionModel(const BarGeometry& g, const ElasticBulk& bulk, double cellSize) {
  HalfModel m;
  m.bulk = bulk;
  const double half = 0.5 * g.length;
  m.mesh = structuredMesh(gridLines(0.0, half, {}, cellSize), gridLines(0.0, g.height, {}, cellSize), {});
  std::vector<bool> fixed(2 * m.mesh.nodes.size(), false);
  symmetryLine(m, fixed, 0, 0.0, 0.0, g.height, 1.0);
  fixed[2 * requireNode(m.mesh, 0.0, 0.0, "bar's corner") + 1] = true;  // y rigid-body mode
  std::vector<int> tie;
  for (int n : m.mesh.nodesIn({half, -1.0, half, g.height + 1.0})) tie.push_back(2 * n);
  numberEquations(m, fixed, {tie});
  finishInterface(m, 0);
  m.loadPattern[0] = 1.0;
  m.loadScale = 1.0;
  m.loadDisplacementScale = 2.0;
  m.control[0] = 2.0;
  m.controlName = "delta";
  return m;
}

}  // namespace ecm::cohesive
