// The implicit solver's linear algebra on the DEN 4b meshes (docs/implicit.md): factorising the
// tangent over the unknowns, the cost every Newton iteration pays, with each sparse LU the build
// offers. The matrix is the tangent of the first load step of den-4b-coarse-implicit.yaml (and
// the same scene on the medium mesh); its pattern is that of every step.
#include <benchmark/benchmark.h>

#include <malloc.h>

#include <Eigen/SparseLU>
#include <algorithm>
#include <chrono>
#include <map>
#include <vector>

#include "mpm/implicit/amg_solver.hpp"
#include "mpm/implicit/gmres.hpp"
#include "mpm/implicit/linear_solver.hpp"
#include "mpm/implicit/implicit_solver.hpp"
#include "mpm/scene/scene_yaml.hpp"
#ifdef ECM_HAVE_UMFPACK
#include <Eigen/UmfPackSupport>
#endif

namespace {

using Matrix = Eigen::SparseMatrix<double>;

struct Tangent {
  Matrix k;
  std::vector<int> components;  // x or y, per unknown (for AMG)
};

// The tangent of the DEN coarse (0), medium (1) or fine (2) mesh.
const Tangent& denTangentAndComponents(int mesh) {
  static std::map<int, Tangent> cache;
  if (auto it = cache.find(mesh); it != cache.end()) return it->second;
  ecm::mpm::Scene scene = ecm::mpm::loadSceneFile(ECM_SOURCE_DIR "/data/den/den-4b-coarse-implicit.yaml");
  if (mesh > 0) {  // the medium and fine meshes of data/den/den-4b-medium.yaml and -fine.yaml
    const double h = mesh == 1 ? 1.25 : 0.625;
    scene.grid.cellSize = ecm::Vec2(h, h);
    scene.grid.origin = ecm::Vec2(-h, -h);
    scene.grid.cellsX = scene.grid.cellsY = mesh == 1 ? 162 : 322;
  }
  ecm::mpm::ImplicitSolver solver(scene, 1);
  Tangent& t = cache[mesh];
  t.k = solver.tangentAtStart(0.001, &t.components);
  return t;
}

const Matrix& denTangent(int mesh) { return denTangentAndComponents(mesh).k; }

// A step's set-up (stencils, unknowns, K's pattern) and one trial with the tangent assembled: the
// rest of a Newton iteration's cost. range(0): mesh; range(1): threads.
void BM_TangentAtStart(benchmark::State& state) {
  ecm::mpm::Scene scene = ecm::mpm::loadSceneFile(ECM_SOURCE_DIR "/data/den/den-4b-coarse-implicit.yaml");
  ecm::mpm::ImplicitSolver solver(scene, static_cast<int>(state.range(1)));
  for (auto _ : state) benchmark::DoNotOptimize(solver.tangentAtStart(0.001).nonZeros());
}
BENCHMARK(BM_TangentAtStart)->Args({0, 1})->Args({0, 2})->Unit(benchmark::kMillisecond);

// Eigen's SparseLU with its COLAMD ordering (the default) and with AMD's.
template <class Ordering>
void BM_SparseLU(benchmark::State& state) {
  const Matrix& k = denTangent(static_cast<int>(state.range(0)));
  Eigen::SparseLU<Matrix, Ordering> lu;
  lu.analyzePattern(k);
  for (auto _ : state) {
    lu.factorize(k);
    benchmark::DoNotOptimize(lu.info());
  }
  state.counters["unknowns"] = static_cast<double>(k.rows());
}
BENCHMARK_TEMPLATE(BM_SparseLU, Eigen::COLAMDOrdering<int>)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);
BENCHMARK_TEMPLATE(BM_SparseLU, Eigen::AMDOrdering<int>)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

#ifdef ECM_HAVE_UMFPACK
// range(1): 0 UMFPACK's automatic strategy, 1 its symmetric strategy (AMD on K + K^T, diagonal
// pivots preferred: the tangent is structurally symmetric), 2 the symmetric strategy with METIS's
// nested dissection instead of AMD.
void BM_Umfpack(benchmark::State& state) {
  const Matrix& k = denTangent(static_cast<int>(state.range(0)));
  Eigen::UmfPackLU<Matrix> lu;
  if (state.range(1) >= 1) lu.umfpackControl()(UMFPACK_STRATEGY) = UMFPACK_STRATEGY_SYMMETRIC;
  if (state.range(1) == 2) lu.umfpackControl()(UMFPACK_ORDERING) = UMFPACK_ORDERING_METIS;
  const auto heapBefore = mallinfo2().uordblks;
  lu.analyzePattern(k);
  lu.factorize(k);
  // The heap the factors hold (with the symbolic analysis), as BM_AmgSolve's.
  const double held = static_cast<double>(mallinfo2().uordblks) - static_cast<double>(heapBefore);
  for (auto _ : state) {
    lu.factorize(k);
    benchmark::DoNotOptimize(lu.info());
  }
  state.counters["unknowns"] = static_cast<double>(k.rows());
  state.counters["bytes_per_unknown"] = held / static_cast<double>(k.rows());
}
BENCHMARK(BM_Umfpack)->Args({0, 0})->Args({0, 1})->Args({0, 2})->Args({1, 0})->Args({1, 1})->Args({1, 2})->Args({2, 1})->Args({2, 2})->Unit(benchmark::kMillisecond);

void BM_UmfpackSolve(benchmark::State& state) {
  const Matrix& k = denTangent(static_cast<int>(state.range(0)));
  Eigen::UmfPackLU<Matrix> lu;
  lu.umfpackControl()(UMFPACK_STRATEGY) = UMFPACK_STRATEGY_SYMMETRIC;
  lu.umfpackControl()(UMFPACK_IRSTEP) = static_cast<double>(state.range(1));
  lu.compute(k);
  const Eigen::VectorXd b = Eigen::VectorXd::Ones(k.rows());
  for (auto _ : state) benchmark::DoNotOptimize(lu.solve(b).eval());
}
// range(1): UMFPACK's steps of iterative refinement (its default is 2).
BENCHMARK(BM_UmfpackSolve)->Args({0, 0})->Args({0, 2})->Args({1, 0})->Args({1, 2})->Args({2, 0})->Unit(benchmark::kMillisecond);
#endif

#ifdef ECM_HAVE_UMFPACK
// The kept factors by runs (mpm/implicit/factor_runs.hpp; docs/implicit.md): a solve with the
// copy against UMFPACK's own solve, the copy's cost (its first solve less a later one; again for
// a second factorisation, whose copy checks the split of the lines for two threads instead of
// finding it) and the heap it holds per unknown. range(0): mesh; range(1): threads.
void BM_FactorRuns(benchmark::State& state) {
  using Clock = std::chrono::steady_clock;
  const Matrix& k = denTangent(static_cast<int>(state.range(0)));
  ecm::mpm::LinearSolver lu(ecm::mpm::LinearSolverKind::Umfpack);
  lu.setCopyAfter(7);  // six solves of UMFPACK's own first
  lu.setThreads(static_cast<int>(state.range(1)));
  lu.factorize(k);
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(k.rows(), -1.0, 2.0);
  const Eigen::VectorXd exact = lu.solve(b);
  auto t = Clock::now();
  for (int i = 0; i < 5; ++i) benchmark::DoNotOptimize(lu.solve(b).data());
  const double umfpack = std::chrono::duration<double>(Clock::now() - t).count() / 5.0;
  const auto heapBefore = mallinfo2().uordblks;
  t = Clock::now();
  const Eigen::VectorXd first = lu.solve(b);
  const double firstSolve = std::chrono::duration<double>(Clock::now() - t).count();
  const double held = static_cast<double>(mallinfo2().uordblks) - static_cast<double>(heapBefore);
  double seconds = 0.0;
  long solves = 0;
  for (auto _ : state) {
    t = Clock::now();
    benchmark::DoNotOptimize(lu.solve(b).data());
    seconds += std::chrono::duration<double>(Clock::now() - t).count();
    ++solves;
  }
  const double copySolve = seconds / static_cast<double>(std::max(solves, 1L));
  // A later factorisation of the same analysis: its copy checks the split found above.
  lu.setCopyAfter(1);
  lu.factorize(k);
  t = Clock::now();
  benchmark::DoNotOptimize(lu.solve(b).data());
  const double again = std::chrono::duration<double>(Clock::now() - t).count() - copySolve;
  const auto n = static_cast<double>(k.rows());
  state.counters["unknowns"] = n;
  state.counters["umfpack_solve_ms"] = 1e3 * umfpack;
  state.counters["copy_solve_ms"] = 1e3 * copySolve;
  state.counters["copy_ms"] = 1e3 * (firstSolve - copySolve);
  state.counters["copy_again_ms"] = 1e3 * again;
  state.counters["copy_bytes_per_unknown"] = held / n;
  state.counters["relative_difference"] = (first - exact).norm() / exact.norm();
}
BENCHMARK(BM_FactorRuns)->ArgsProduct({{0, 1, 2}, {1, 2}})->Unit(benchmark::kMillisecond);
#endif

// Krylov on the kept factorisation (ImplicitSettings::krylovIterations; docs/implicit.md): what a
// GMRES vector costs (a solve with the kept LU, a product with K, the orthogonalisation) against
// one factorisation, through the solver's own LinearSolver. Their ratio, `break_even`, is the
// most Krylov vectors a Newton step may spend before a fresh factorisation would have been
// cheaper. The current tangent is the kept one with every 50th column halved (softened points);
// the vector budget is 20. range(0): mesh.
void BM_KrylovOnKeptLU(benchmark::State& state) {
  using Clock = std::chrono::steady_clock;
  const Matrix& kept = denTangent(static_cast<int>(state.range(0)));
  ecm::mpm::LinearSolver lu(ecm::mpm::defaultLinearSolver());
  lu.factorize(kept);  // the analysis, once
  const auto start = Clock::now();
  lu.factorize(kept);
  const double factorisation = std::chrono::duration<double>(Clock::now() - start).count();
  Matrix current = kept;
  for (Eigen::Index j = 0; j < current.outerSize(); j += 50)
    for (Matrix::InnerIterator it(current, j); it; ++it) it.valueRef() *= 0.5;
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(kept.rows(), -1.0, 2.0);
  Eigen::VectorXd x;
  long vectors = 0;
  double seconds = 0.0;
  for (auto _ : state) {
    const auto t0 = Clock::now();
    const ecm::mpm::GmresResult r = ecm::mpm::gmres([&](const Eigen::VectorXd& v) -> Eigen::VectorXd { return current * v; },
                                                    [&](const Eigen::VectorXd& v) { return lu.solve(v); }, b, 1e-3, 20, x);
    seconds += std::chrono::duration<double>(Clock::now() - t0).count();
    vectors += r.iterations;
  }
  const double perVector = seconds / static_cast<double>(std::max(vectors, 1L));
  state.counters["unknowns"] = static_cast<double>(kept.rows());
  state.counters["vectors"] = static_cast<double>(vectors) / static_cast<double>(state.iterations());
  state.counters["ms_per_vector"] = 1e3 * perVector;
  state.counters["factorisation_ms"] = 1e3 * factorisation;
  state.counters["break_even"] = factorisation / perVector;
}
BENCHMARK(BM_KrylovOnKeptLU)->Arg(0)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond);

#ifdef ECM_HAVE_HYPRE
// GMRES preconditioned by BoomerAMG (linear_solver: amg) on the same tangents: a solve with the
// hierarchy kept (the time per solve, the iterations, the time per iteration) and, once, the
// hierarchy's setup and the solver's memory per unknown (the heap it holds after its first solve:
// hypre's copy of K, the hierarchy, GMRES's Krylov vectors). The start's tangent is elastic: once
// bands soften a solve takes 2-4 times the iterations (docs/implicit.md, "The AMG solver").
// range(0): mesh; range(1): the options, 0 the defaults, 1 strong threshold 0.25, 2 one level
// coarsened aggressively, 3 l1 symmetric Gauss-Seidel, 4 l1-Jacobi (two sweeps), 5 a restart of 20,
// 6 no ILU(0) on the finest level (hybrid Gauss-Seidel on every level: the defaults before 2026-12-04).
ecm::mpm::AmgOptions amgVariant(int v) {
  ecm::mpm::AmgOptions o;
  if (v == 1) o.strongThreshold = 0.25;
  if (v == 2) o.aggressiveLevels = 1;
  if (v == 3) o.relaxType = 8;
  if (v == 4) o.relaxType = 18, o.sweeps = 2;
  if (v == 5) o.krylovDimension = 20;
  if (v == 6) o.iluLevels = 0;
  return o;
}

void BM_AmgSolve(benchmark::State& state) {
  const Tangent& t = denTangentAndComponents(static_cast<int>(state.range(0)));
  const auto heapBefore = mallinfo2().uordblks;
  ecm::mpm::AmgSolver amg;
  amg.options = amgVariant(static_cast<int>(state.range(1)));
  amg.setComponents(t.components);
  amg.setMatrix(t.k);
  const Eigen::VectorXd b = Eigen::VectorXd::Ones(t.k.rows());
  Eigen::VectorXd x;
  if (!amg.solve(b, x)) state.SkipWithError("GMRES did not converge");
  const double held = static_cast<double>(mallinfo2().uordblks) - static_cast<double>(heapBefore);
  const double setup = amg.statistics().setupSeconds;
  long iterations = 0, solves = 0;
  const double start = amg.statistics().solveSeconds;
  for (auto _ : state) {
    benchmark::DoNotOptimize(amg.solve(b, x));
    iterations += amg.lastIterations();
    ++solves;
  }
  const double solving = amg.statistics().solveSeconds - start;
  const auto n = static_cast<double>(t.k.rows());
  state.counters["unknowns"] = n;
  state.counters["setup_ms"] = 1e3 * setup;
  state.counters["iterations"] = static_cast<double>(iterations) / static_cast<double>(std::max(solves, 1L));
  state.counters["ms_per_iteration"] = 1e3 * solving / static_cast<double>(std::max(iterations, 1L));
  state.counters["bytes_per_unknown"] = held / n;
  state.counters["K_bytes_per_unknown"] = static_cast<double>(t.k.nonZeros()) * 12.0 / n;  // values and columns
}
BENCHMARK(BM_AmgSolve)
    ->ArgsProduct({{0, 1}, {0, 1, 2, 3, 4, 5, 6}})
    ->Args({2, 0})
    ->Unit(benchmark::kMillisecond);
#endif

}  // namespace
