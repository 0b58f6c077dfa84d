#include "mpm/implicit/factor_runs.hpp"

namespace ecm::mpm {

namespace {

using Run = Eigen::Map<Eigen::VectorXd>;
using ConstRun = Eigen::Map<const Eigen::VectorXd>;

}  // namespace

RunTriangle runsOf(int n, const std::int32_t* pointers, const std::int32_t* indices, const double* values,
                   bool lastIsDiagonal) {
  RunTriangle t;
  t.firstRun.reserve(static_cast<std::size_t>(n) + 1);
  t.firstValue.reserve(static_cast<std::size_t>(n) + 1);
  t.values.reserve(static_cast<std::size_t>(pointers[n] - pointers[0]));
  for (int i = 0; i < n; ++i) {
    t.firstRun.push_back(static_cast<std::int32_t>(t.runStart.size()));
    t.firstValue.push_back(static_cast<std::int32_t>(t.values.size()));
    const std::int32_t end = pointers[i + 1] - (lastIsDiagonal ? 1 : 0);
    for (std::int32_t e = pointers[i]; e < end; ++e) {
      if (e == pointers[i] || indices[e] != indices[e - 1] + 1) {
        t.runStart.push_back(indices[e]);
        t.runLength.push_back(0);
      }
      ++t.runLength.back();
      t.values.push_back(values[e]);
    }
  }
  t.firstRun.push_back(static_cast<std::int32_t>(t.runStart.size()));
  t.firstValue.push_back(static_cast<std::int32_t>(t.values.size()));
  return t;
}

void solveByRuns(const FactorRuns& f, const Eigen::VectorXd& b, Eigen::VectorXd& x, std::vector<double>& work) {
  const int n = f.n;
  work.resize(static_cast<std::size_t>(n));
  double* w = work.data();
  for (int k = 0; k < n; ++k) {
    const std::int32_t i = f.rowOfPivot[static_cast<std::size_t>(k)];
    w[k] = f.rowScale[static_cast<std::size_t>(i)] * b[i];
  }
  const RunTriangle& l = f.lower;
  for (std::size_t i = 0; i < static_cast<std::size_t>(n); ++i) {  // L y = P R b, row by row
    const double* value = l.values.data() + l.firstValue[i];
    double sum = 0.0;
    for (std::int32_t r = l.firstRun[i]; r < l.firstRun[i + 1]; ++r) {
      const std::int32_t length = l.runLength[static_cast<std::size_t>(r)];
      sum += ConstRun(value, length).dot(ConstRun(w + l.runStart[static_cast<std::size_t>(r)], length));
      value += length;
    }
    w[i] -= sum;
  }
  const RunTriangle& u = f.upper;
  for (std::size_t j = static_cast<std::size_t>(n); j-- > 0;) {  // U z = y, column by column
    const double z = w[j] / f.diagonal[j];
    w[j] = z;
    const double* value = u.values.data() + u.firstValue[j];
    for (std::int32_t r = u.firstRun[j]; r < u.firstRun[j + 1]; ++r) {
      const std::int32_t length = u.runLength[static_cast<std::size_t>(r)];
      Run(w + u.runStart[static_cast<std::size_t>(r)], length) -= z * ConstRun(value, length);
      value += length;
    }
  }
  x.resize(n);
  for (int k = 0; k < n; ++k) x[f.columnOfPivot[static_cast<std::size_t>(k)]] = w[k];
}

}  // namespace ecm::mpm
