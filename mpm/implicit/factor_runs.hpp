#pragma once
// A sparse LU's factors copied line by line (the rows of L, the columns of U), each line stored
// as runs of consecutive indices: every solve with a factorisation, Krylov's preconditioning
// solves on the kept one above all (docs/implicit.md, "The kept factors by runs"). The same factors in double precision, only
// stored for the solve: a run is read as one contiguous vector (a dot product for a row of L, an
// update for a column of U) and takes one index, not one per entry.
#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace ecm::mpm {

// One triangle by lines, without its diagonal. Line i's runs are [firstRun[i], firstRun[i + 1]);
// run r covers indices runStart[r] .. runStart[r] + runLength[r] - 1; line i's values start at
// firstValue[i] and follow its runs in order.
struct RunTriangle {
  std::vector<std::int32_t> firstRun;
  std::vector<std::int32_t> firstValue;
  std::vector<std::int32_t> runStart;
  std::vector<std::int32_t> runLength;
  std::vector<double> values;
};

// Two groups of lines that two threads may solve at once (docs/implicit.md, "Two threads on the
// kept factors"): the lines below serialFrom fall into groups[0] and groups[1] (each ascending),
// and no entry of L or U joins a line of one group to a line of the other. The lines from
// serialFrom on (the top separators of the ordering) are solved by one thread: for L after the
// groups, for U before them. Empty groups: no useful split, one thread throughout.
struct TwoWaySplit {
  std::int32_t serialFrom = 0;
  std::vector<std::int32_t> groups[2];
  bool empty() const { return groups[0].empty() || groups[1].empty(); }
};

// P R A Q = L U: A's row rowOfPivot[k] is the k-th pivot row and its column columnOfPivot[k] the
// k-th pivot column; rowScale[i] multiplies row i of A; L has a unit diagonal.
struct FactorRuns {
  int n = 0;
  std::vector<std::int32_t> rowOfPivot, columnOfPivot;
  std::vector<double> rowScale;
  RunTriangle lower;  // the rows of L left of the diagonal
  RunTriangle upper;  // the columns of U above the diagonal
  std::vector<double> diagonal;  // U's
  TwoWaySplit split;
};

// The runs of a compressed triangle's lines (pointers n + 1, each line's indices sorted), with
// each line's last entry left out when lastIsDiagonal (UMFPACK puts the diagonal last in the
// rows of L and in the columns of U).
RunTriangle runsOf(int n, const std::int32_t* pointers, const std::int32_t* indices, const double* values,
                   bool lastIsDiagonal);

// The split of f's lines that minimises the longer thread's entries plus the serial lines'
// (groups of whole components of the lines below serialFrom, the larger ones first). Where
// `previous` (the split of an earlier factorisation of the same analysis) holds for f's entries,
// it is returned as it is: checking a split costs a look per run, finding one a look per entry.
TwoWaySplit splitOf(const FactorRuns& f, const TwoWaySplit* previous = nullptr);

// Whether no entry of f joins a line of one of s's groups to a line of the other.
bool holds(const TwoWaySplit& s, const FactorRuns& f);

// x = A^-1 b; `work` is scratch (n values), kept by the caller between solves. On two threads
// where f.split is not empty; the answer is bitwise the same on one thread or two (each entry of
// x sees the same operations in the same order).
void solveByRuns(const FactorRuns& f, const Eigen::VectorXd& b, Eigen::VectorXd& x, std::vector<double>& work,
                 int threads = 1);

}  // namespace ecm::mpm
