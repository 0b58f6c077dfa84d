#pragma once
// A sparse LU's factors copied line by line (the rows of L, the columns of U), each line stored
// as runs of consecutive indices: the preconditioner's solve of Krylov on the kept factorisation
// (docs/implicit.md, "The kept factors by runs"). The same factors in double precision, only
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

// P R A Q = L U: A's row rowOfPivot[k] is the k-th pivot row and its column columnOfPivot[k] the
// k-th pivot column; rowScale[i] multiplies row i of A; L has a unit diagonal.
struct FactorRuns {
  int n = 0;
  std::vector<std::int32_t> rowOfPivot, columnOfPivot;
  std::vector<double> rowScale;
  RunTriangle lower;  // the rows of L left of the diagonal
  RunTriangle upper;  // the columns of U above the diagonal
  std::vector<double> diagonal;  // U's
};

// The runs of a compressed triangle's lines (pointers n + 1, each line's indices sorted), with
// each line's last entry left out when lastIsDiagonal (UMFPACK puts the diagonal last in the
// rows of L and in the columns of U).
RunTriangle runsOf(int n, const std::int32_t* pointers, const std::int32_t* indices, const double* values,
                   bool lastIsDiagonal);

// x = A^-1 b; `work` is scratch (n values), kept by the caller between solves.
void solveByRuns(const FactorRuns& f, const Eigen::VectorXd& b, Eigen::VectorXd& x, std::vector<double>& work);

}  // namespace ecm::mpm
