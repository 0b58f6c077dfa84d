#include "mpm/implicit/gmres.hpp"

#include <cmath>
#include <vector>

namespace ecm::mpm {

GmresResult gmres(const LinearMap& apply, const LinearMap& precondition, const Eigen::VectorXd& b, double tolerance,
                  int maxIterations, Eigen::VectorXd& x) {
  GmresResult result;
  x = Eigen::VectorXd::Zero(b.size());
  const double beta = b.norm();
  if (beta == 0.0) {
    result.converged = true;
    return result;
  }
  const int m = std::max(maxIterations, 1);
  std::vector<Eigen::VectorXd> v;  // the Arnoldi basis
  std::vector<Eigen::VectorXd> z;  // M^-1 of each basis vector: x = sum_j y_j z_j
  v.reserve(static_cast<std::size_t>(m) + 1);
  z.reserve(static_cast<std::size_t>(m));
  Eigen::MatrixXd h = Eigen::MatrixXd::Zero(m + 1, m);  // Hessenberg, rotated to upper triangular as it grows
  Eigen::VectorXd cs = Eigen::VectorXd::Zero(m), sn = Eigen::VectorXd::Zero(m);
  Eigen::VectorXd g = Eigen::VectorXd::Zero(m + 1);  // the rotated right-hand side beta e_1
  g[0] = beta;
  v.push_back(b / beta);
  int k = 0;
  while (k < m) {
    z.push_back(precondition(v[static_cast<std::size_t>(k)]));
    Eigen::VectorXd w = apply(z.back());
    for (int i = 0; i <= k; ++i) {  // modified Gram-Schmidt
      h(i, k) = w.dot(v[static_cast<std::size_t>(i)]);
      w -= h(i, k) * v[static_cast<std::size_t>(i)];
    }
    h(k + 1, k) = w.norm();
    for (int i = 0; i < k; ++i) {  // the earlier rotations on the new column
      const double t = cs[i] * h(i, k) + sn[i] * h(i + 1, k);
      h(i + 1, k) = -sn[i] * h(i, k) + cs[i] * h(i + 1, k);
      h(i, k) = t;
    }
    const double rho = std::hypot(h(k, k), h(k + 1, k));  // the rotation that zeroes h(k + 1, k)
    cs[k] = rho == 0.0 ? 1.0 : h(k, k) / rho;
    sn[k] = rho == 0.0 ? 0.0 : h(k + 1, k) / rho;
    h(k, k) = rho;
    h(k + 1, k) = 0.0;
    g[k + 1] = -sn[k] * g[k];
    g[k] = cs[k] * g[k];
    const double subdiagonal = w.norm();
    ++k;
    result.relativeResidual = std::abs(g[k]) / beta;
    if (result.relativeResidual <= tolerance || subdiagonal == 0.0 || !std::isfinite(result.relativeResidual)) break;
    v.push_back(w / subdiagonal);
  }
  result.iterations = k;
  result.converged = result.relativeResidual <= tolerance;
  // y from the triangular system, x = Z y.
  const Eigen::VectorXd y = h.topLeftCorner(k, k).triangularView<Eigen::Upper>().solve(g.head(k));
  if (!y.allFinite()) {
    result.converged = false;
    return result;
  }
  for (int j = 0; j < k; ++j) x += y[j] * z[static_cast<std::size_t>(j)];
  return result;
}

}  // namespace ecm::mpm
