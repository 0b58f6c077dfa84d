#include "mpm/implicit/factor_runs.hpp"

#include <algorithm>
#include <numeric>
#include <omp.h>

namespace ecm::mpm {

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

namespace {

using Run = Eigen::Map<Eigen::VectorXd>;
using ConstRun = Eigen::Map<const Eigen::VectorXd>;

// Joins the lines that share an entry of L or U (union by work, path halving).
class LineComponents {
 public:
  explicit LineComponents(int n) : parent_(static_cast<std::size_t>(n)), work_(static_cast<std::size_t>(n), 0) {
    std::iota(parent_.begin(), parent_.end(), 0);
  }
  std::int32_t find(std::int32_t i) {
    while (parent_[static_cast<std::size_t>(i)] != i) {
      auto& p = parent_[static_cast<std::size_t>(i)];
      p = parent_[static_cast<std::size_t>(p)];
      i = p;
    }
    return i;
  }
  // Adds line k with its work and joins it with the lines its runs reach; the root of k after.
  std::int32_t add(std::int32_t k, std::int64_t work, const RunTriangle* const (&triangles)[2]) {
    work_[static_cast<std::size_t>(k)] = work;
    std::int32_t root = k;
    for (const RunTriangle* t : triangles)
      for (std::int32_t r = t->firstRun[static_cast<std::size_t>(k)]; r < t->firstRun[static_cast<std::size_t>(k) + 1]; ++r) {
        const std::int32_t start = t->runStart[static_cast<std::size_t>(r)];
        for (std::int32_t i = start; i < start + t->runLength[static_cast<std::size_t>(r)]; ++i) root = join(root, find(i));
      }
    return root;
  }
  std::int64_t work(std::int32_t root) const { return work_[static_cast<std::size_t>(root)]; }

 private:
  std::int32_t join(std::int32_t a, std::int32_t b) {
    if (a == b) return a;
    if (work_[static_cast<std::size_t>(a)] < work_[static_cast<std::size_t>(b)]) std::swap(a, b);
    parent_[static_cast<std::size_t>(b)] = a;
    work_[static_cast<std::size_t>(a)] += work_[static_cast<std::size_t>(b)];
    return a;
  }
  std::vector<std::int32_t> parent_;
  std::vector<std::int64_t> work_;
};

// A line's work in a solve: its entries in L's row and U's column, and its diagonal.
std::int64_t lineWork(const FactorRuns& f, std::size_t k) {
  return 1 + (f.lower.firstValue[k + 1] - f.lower.firstValue[k]) + (f.upper.firstValue[k + 1] - f.upper.firstValue[k]);
}

// Row i of L y = P R b: w[i] -= L(i, :) w.
inline void lowerRow(const RunTriangle& l, std::size_t i, double* w) {
  const double* value = l.values.data() + l.firstValue[i];
  double sum = 0.0;
  for (std::int32_t r = l.firstRun[i]; r < l.firstRun[i + 1]; ++r) {
    const std::int32_t length = l.runLength[static_cast<std::size_t>(r)];
    sum += ConstRun(value, length).dot(ConstRun(w + l.runStart[static_cast<std::size_t>(r)], length));
    value += length;
  }
  w[i] -= sum;
}

// Column j of U z = y: z_j, then w -= U(:, j) z_j.
inline void upperColumn(const RunTriangle& u, const std::vector<double>& diagonal, std::size_t j, double* w) {
  const double z = w[j] / diagonal[j];
  w[j] = z;
  const double* value = u.values.data() + u.firstValue[j];
  for (std::int32_t r = u.firstRun[j]; r < u.firstRun[j + 1]; ++r) {
    const std::int32_t length = u.runLength[static_cast<std::size_t>(r)];
    Run(w + u.runStart[static_cast<std::size_t>(r)], length) -= z * ConstRun(value, length);
    value += length;
  }
}

}  // namespace

bool holds(const TwoWaySplit& s, const FactorRuns& f) {
  if (s.empty() || s.serialFrom > f.n) return false;
  // Each line's group, and where the stretch of lines of that group starting at it ends.
  const auto serialFrom = static_cast<std::size_t>(s.serialFrom);
  std::vector<std::int8_t> group(serialFrom, -1);
  for (int g = 0; g < 2; ++g)
    for (const std::int32_t k : s.groups[g]) group[static_cast<std::size_t>(k)] = static_cast<std::int8_t>(g);
  std::vector<std::int32_t> stretchEnd(serialFrom);
  for (std::size_t k = serialFrom; k-- > 0;)
    stretchEnd[k] = k + 1 < serialFrom && group[k + 1] == group[k] ? stretchEnd[k + 1] : static_cast<std::int32_t>(k + 1);
  for (std::size_t k = 0; k < serialFrom; ++k) {
    if (group[k] < 0) return false;
    for (const RunTriangle* t : {&f.lower, &f.upper})
      for (std::int32_t r = t->firstRun[k]; r < t->firstRun[k + 1]; ++r) {
        const std::int32_t start = t->runStart[static_cast<std::size_t>(r)];
        // (The runs of line k lie below k, so below serialFrom.)
        if (group[static_cast<std::size_t>(start)] != group[k] ||
            stretchEnd[static_cast<std::size_t>(start)] < start + t->runLength[static_cast<std::size_t>(r)])
          return false;
      }
  }
  return true;
}

TwoWaySplit splitOf(const FactorRuns& f, const TwoWaySplit* previous) {
  if (previous && holds(*previous, f)) return *previous;
  const std::int32_t n = f.n;
  const RunTriangle* const triangles[2] = {&f.lower, &f.upper};
  std::int64_t all = 0;
  for (std::size_t k = 0; k < static_cast<std::size_t>(n); ++k) all += lineWork(f, k);
  // The prefix of lines whose split costs least: the longer thread at best (the prefix's largest
  // component, or half the prefix) plus the lines after it, on one thread.
  std::int32_t serialFrom = 0;
  std::int64_t best = all, prefix = 0, largest = 0;
  {
    LineComponents c(n);
    for (std::int32_t k = 0; k < n; ++k) {
      const std::int64_t w = lineWork(f, static_cast<std::size_t>(k));
      prefix += w;
      largest = std::max(largest, c.work(c.add(k, w, triangles)));
      const std::int64_t cost = std::max(largest, (prefix + 1) / 2) + (all - prefix);
      if (cost < best) best = cost, serialFrom = k + 1;
    }
  }
  TwoWaySplit split;
  if (serialFrom == 0) return split;
  // The prefix's components, the larger first, each to the group with less work so far.
  LineComponents c(serialFrom);
  for (std::int32_t k = 0; k < serialFrom; ++k) c.add(k, lineWork(f, static_cast<std::size_t>(k)), triangles);
  std::vector<std::int32_t> roots;
  for (std::int32_t k = 0; k < serialFrom; ++k)
    if (c.find(k) == k) roots.push_back(k);
  std::stable_sort(roots.begin(), roots.end(), [&](std::int32_t a, std::int32_t b) { return c.work(a) > c.work(b); });
  std::vector<std::int8_t> groupOfRoot(static_cast<std::size_t>(serialFrom), 0);
  std::int64_t load[2] = {0, 0};
  for (const std::int32_t r : roots) {
    const int g = load[1] < load[0] ? 1 : 0;
    groupOfRoot[static_cast<std::size_t>(r)] = static_cast<std::int8_t>(g);
    load[g] += c.work(r);
  }
  split.serialFrom = serialFrom;
  for (std::int32_t k = 0; k < serialFrom; ++k) split.groups[groupOfRoot[static_cast<std::size_t>(c.find(k))]].push_back(k);
  return split;
}

void solveByRuns(const FactorRuns& f, const Eigen::VectorXd& b, Eigen::VectorXd& x, std::vector<double>& work,
                 int threads) {
  const int n = f.n;
  work.resize(static_cast<std::size_t>(n));
  double* w = work.data();
  for (int k = 0; k < n; ++k) {
    const std::int32_t i = f.rowOfPivot[static_cast<std::size_t>(k)];
    w[k] = f.rowScale[static_cast<std::size_t>(i)] * b[i];
  }
  const auto count = static_cast<std::size_t>(n);
  if (threads < 2 || f.split.empty()) {
    for (std::size_t i = 0; i < count; ++i) lowerRow(f.lower, i, w);  // L y = P R b, row by row
    for (std::size_t j = count; j-- > 0;) upperColumn(f.upper, f.diagonal, j, w);  // U z = y, column by column
  } else {
    // Each group's rows of L, then the tail's; the tail's columns of U, then each group's.
    const TwoWaySplit& s = f.split;
    const auto serialFrom = static_cast<std::size_t>(s.serialFrom);
#pragma omp parallel num_threads(2)
    {
      const std::vector<std::int32_t>& mine = s.groups[omp_get_thread_num()];
      for (const std::int32_t i : mine) lowerRow(f.lower, static_cast<std::size_t>(i), w);
#pragma omp barrier
#pragma omp single
      {
        for (std::size_t i = serialFrom; i < count; ++i) lowerRow(f.lower, i, w);
        for (std::size_t j = count; j-- > serialFrom;) upperColumn(f.upper, f.diagonal, j, w);
      }
      for (auto j = mine.rbegin(); j != mine.rend(); ++j) upperColumn(f.upper, f.diagonal, static_cast<std::size_t>(*j), w);
    }
  }
  x.resize(n);
  for (int k = 0; k < n; ++k) x[f.columnOfPivot[static_cast<std::size_t>(k)]] = w[k];
}

}  // namespace ecm::mpm
