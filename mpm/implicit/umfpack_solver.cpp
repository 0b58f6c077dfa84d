// UMFPACK as the implicit steps' LU (mpm/implicit/linear_solver_backend.hpp), its library loaded at
// the first use (mpm/implicit/umfpack_library.hpp). Built only where the build found UMFPACK.
#include <algorithm>
#include <array>
#include <memory>
#include <optional>
#include <vector>

#include "mpm/implicit/factor_runs.hpp"
#include "mpm/implicit/linear_solver_backend.hpp"
#include "mpm/implicit/umfpack_library.hpp"

namespace ecm::mpm {

namespace {

struct UmfpackFactors {
  const UmfpackLibrary& lib = umfpackLibrary();
  std::array<double, UMFPACK_CONTROL> control{};
  std::array<double, UMFPACK_INFO> info{};
  void* symbolic = nullptr;
  void* numeric = nullptr;
  Eigen::SparseMatrix<double> k;  // the factorised matrix (compressed), which the solves pass on

  UmfpackFactors() {
    lib.defaults(control.data());
    // The symmetric strategy (AMD on K + K^T, diagonal pivots preferred): K is structurally
    // symmetric and nearly so in value. No iterative refinement: Newton corrects the solve.
    // Measured in bench/implicit_bench.cpp (docs/implicit.md).
    control[UMFPACK_STRATEGY] = UMFPACK_STRATEGY_SYMMETRIC;
    control[UMFPACK_IRSTEP] = 0;
  }
  ~UmfpackFactors() {
    if (numeric) lib.freeNumeric(&numeric);
    if (symbolic) lib.freeSymbolic(&symbolic);
  }
  UmfpackFactors(const UmfpackFactors&) = delete;
  UmfpackFactors& operator=(const UmfpackFactors&) = delete;

  bool analyse(const Eigen::SparseMatrix<double>& pattern) {
    split.reset();
    if (numeric) lib.freeNumeric(&numeric);
    if (symbolic) lib.freeSymbolic(&symbolic);
    Eigen::SparseMatrix<double> m = patternOnes(pattern);
    m.makeCompressed();
    return lib.symbolic(static_cast<int>(m.rows()), static_cast<int>(m.cols()), m.outerIndexPtr(), m.innerIndexPtr(),
                        m.valuePtr(), &symbolic, control.data(), info.data()) == UMFPACK_OK;
  }
  bool factorise(const Eigen::SparseMatrix<double>& matrix) {
    if (numeric) lib.freeNumeric(&numeric);
    runs.reset();
    solves = 0;
    copyTried = false;
    k = matrix;
    k.makeCompressed();
    return lib.numeric(k.outerIndexPtr(), k.innerIndexPtr(), k.valuePtr(), symbolic, &numeric, control.data(),
                       info.data()) == UMFPACK_OK;
  }
  Eigen::VectorXd umfpackSolve(const Eigen::VectorXd& b) {
    Eigen::VectorXd x(b.size());
    lib.solve(UMFPACK_A, k.outerIndexPtr(), k.innerIndexPtr(), k.valuePtr(), x.data(), b.data(), numeric,
              control.data(), info.data());
    return x;
  }

  // The factors copied by runs (mpm/implicit/factor_runs.hpp), made at the copyAfter-th solve
  // with a factorisation (docs/implicit.md, "The kept factors by runs"); the solves before it are
  // UMFPACK's own. The default, the first, keeps restarts bitwise: a restarted run factorises the
  // saved tangent again, and its copy is the one the uninterrupted run made.
  std::unique_ptr<FactorRuns> runs;
  std::optional<TwoWaySplit> split;  // the last copy's, while the analysis stands
  int solves = 0;
  bool copyTried = false;  // of this factorisation (a copy that failed is not tried again)
  std::vector<double> work;
  long copies = 0;

  Eigen::VectorXd solve(const Eigen::VectorXd& b, int copyAfter, int threads) {
    if (!copyTried && copyAfter > 0 && ++solves >= copyAfter) copyTried = true, runs = copy(threads);
    if (!runs) return umfpackSolve(b);
    Eigen::VectorXd x;
    solveByRuns(*runs, b, x, work, threads);
    return x;
  }

  // Whether every line (a row of L, a column of U) ends on its diagonal, as runsOf expects.
  static bool endsOnDiagonal(const std::vector<int>& pointers, const std::vector<int>& indices) {
    for (std::size_t i = 0; i + 1 < pointers.size(); ++i)
      if (pointers[i + 1] <= pointers[i] || indices[static_cast<std::size_t>(pointers[i + 1] - 1)] != static_cast<int>(i)) return false;
    return true;
  }
  // L by rows and U by columns, each triangle on a thread of its own where there are two (UMFPACK
  // only reads its numeric object; each call fills arrays of its own), else one after the other
  // (those arrays are the copy's largest transient). Null where UMFPACK refuses, or a line does
  // not end on its diagonal.
  std::unique_ptr<FactorRuns> copy(int threads) {
    int lnz = 0, unz = 0, rows = 0, columns = 0, diagonalEntries = 0;
    if (lib.getLunz(&lnz, &unz, &rows, &columns, &diagonalEntries, numeric) != UMFPACK_OK || rows != columns)
      return nullptr;
    auto f = std::make_unique<FactorRuns>();
    const auto n = static_cast<std::size_t>(rows);
    f->n = rows;
    f->rowOfPivot.resize(n);
    f->columnOfPivot.resize(n);
    f->rowScale.resize(n);
    f->diagonal.resize(n);
    int reciprocal = 0;
    bool copied[2] = {false, false};
    const auto triangle = [&](int which) {
      const std::size_t entries = static_cast<std::size_t>(which == 0 ? lnz : unz);
      std::vector<int> pointers(n + 1), indices(entries);
      std::vector<double> values(entries);
      const int status =
          which == 0 ? lib.getNumeric(pointers.data(), indices.data(), values.data(), nullptr, nullptr, nullptr,
                                      f->rowOfPivot.data(), f->columnOfPivot.data(), f->diagonal.data(), &reciprocal,
                                      f->rowScale.data(), numeric)
                     : lib.getNumeric(nullptr, nullptr, nullptr, pointers.data(), indices.data(), values.data(), nullptr,
                                      nullptr, nullptr, nullptr, nullptr, numeric);
      if (status != UMFPACK_OK || !endsOnDiagonal(pointers, indices)) return;
      (which == 0 ? f->lower : f->upper) = runsOf(rows, pointers.data(), indices.data(), values.data(), true);
      copied[which] = true;
    };
#pragma omp parallel for num_threads(std::min(threads, 2)) schedule(static, 1)
    for (int which = 0; which < 2; ++which) triangle(which);
    if (!copied[0] || !copied[1]) return nullptr;
    if (!reciprocal)
      for (double& s : f->rowScale) s = 1.0 / s;  // UMFPACK divides row i by rowScale[i]
    if (threads >= 2) {  // (one thread has no use for the split)
      f->split = splitOf(*f, split ? &*split : nullptr);
      split = f->split;
    }
    ++copies;
    return f;
  }
};

class UmfpackBackend final : public LinearSolverBackend {
 public:
  explicit UmfpackBackend(const LinearSolverOptions& options) : options_(options) {}
  bool factorize(const Eigen::SparseMatrix<double>& k) override {
    if (!umfpack_) umfpack_ = std::make_unique<UmfpackFactors>();  // loads the library at the first use
    if (!analysed_) {
      if (!umfpack_->analyse(k)) return false;
      analysed_ = true;
    }
    return umfpack_->factorise(k);
  }
  void forgetPattern() override { analysed_ = false; }
  Eigen::VectorXd solve(const Eigen::VectorXd& b) override { return umfpack_->solve(b, options_.copyAfter, options_.threads); }
  std::optional<long> factorCopies() const override { return umfpack_ ? umfpack_->copies : 0; }

 private:
  const LinearSolverOptions& options_;
  bool analysed_ = false;
  std::unique_ptr<UmfpackFactors> umfpack_;
};

}  // namespace

std::unique_ptr<LinearSolverBackend> makeUmfpackBackend(const LinearSolverOptions& options) {
  return std::make_unique<UmfpackBackend>(options);
}

}  // namespace ecm::mpm
