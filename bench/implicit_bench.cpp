// The implicit solver's linear algebra on the DEN 4b meshes (docs/implicit.md): factorising the
// tangent over the unknowns, the cost every Newton iteration pays, with each sparse LU the build
// offers. The matrix is the tangent of the first load step of den-4b-coarse-implicit.yaml (and
// the same scene on the medium mesh); its pattern is that of every step.
#include <benchmark/benchmark.h>

#include <Eigen/SparseLU>
#include <map>

#include "mpm/implicit/implicit_solver.hpp"
#include "mpm/scene/scene_yaml.hpp"
#ifdef ECM_HAVE_UMFPACK
#include <Eigen/UmfPackSupport>
#endif

namespace {

using Matrix = Eigen::SparseMatrix<double>;

// The tangent of the DEN coarse (0), medium (1) or fine (2) mesh.
const Matrix& denTangent(int mesh) {
  static std::map<int, Matrix> cache;
  if (auto it = cache.find(mesh); it != cache.end()) return it->second;
  ecm::mpm::Scene scene = ecm::mpm::loadSceneFile(ECM_SOURCE_DIR "/data/den/den-4b-coarse-implicit.yaml");
  if (mesh > 0) {  // the medium and fine meshes of data/den/den-4b-medium.yaml and -fine.yaml
    const double h = mesh == 1 ? 1.25 : 0.625;
    scene.grid.cellSize = ecm::Vec2(h, h);
    scene.grid.origin = ecm::Vec2(-h, -h);
    scene.grid.cellsX = scene.grid.cellsY = mesh == 1 ? 162 : 322;
  }
  ecm::mpm::ImplicitSolver solver(scene, 1);
  return cache[mesh] = solver.tangentAtStart(0.001);
}

// A step's set-up (stencils, unknowns, K's pattern) and one trial with the tangent assembled: the
// rest of a Newton iteration's cost. range(0): mesh; range(1): threads.
void BM_TangentAtStart(benchmark::State& state) {
  ecm::mpm::Scene scene = ecm::mpm::loadSceneFile(ECM_SOURCE_DIR "/data/den/den-4b-coarse-implicit.yaml");
  ecm::mpm::ImplicitSolver solver(scene, static_cast<int>(state.range(1)));
  for (auto _ : state) benchmark::DoNotOptimize(solver.tangentAtStart(0.001).nonZeros());
}
BENCHMARK(BM_TangentAtStart)->Args({0, 1})->Args({0, 2})->Unit(benchmark::kMillisecond);

void BM_SparseLU(benchmark::State& state) {
  const Matrix& k = denTangent(static_cast<int>(state.range(0)));
  Eigen::SparseLU<Matrix, Eigen::COLAMDOrdering<int>> lu;
  lu.analyzePattern(k);
  for (auto _ : state) {
    lu.factorize(k);
    benchmark::DoNotOptimize(lu.info());
  }
  state.counters["unknowns"] = static_cast<double>(k.rows());
}
BENCHMARK(BM_SparseLU)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

void BM_SparseLUAmd(benchmark::State& state) {
  const Matrix& k = denTangent(static_cast<int>(state.range(0)));
  Eigen::SparseLU<Matrix, Eigen::AMDOrdering<int>> lu;
  lu.analyzePattern(k);
  for (auto _ : state) {
    lu.factorize(k);
    benchmark::DoNotOptimize(lu.info());
  }
  state.counters["unknowns"] = static_cast<double>(k.rows());
}
BENCHMARK(BM_SparseLUAmd)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

#ifdef ECM_HAVE_UMFPACK
// range(1): 0 UMFPACK's automatic strategy, 1 its symmetric strategy (AMD on K + K^T, diagonal
// pivots preferred: the tangent is structurally symmetric), 2 the symmetric strategy with METIS's
// nested dissection instead of AMD.
void BM_Umfpack(benchmark::State& state) {
  const Matrix& k = denTangent(static_cast<int>(state.range(0)));
  Eigen::UmfPackLU<Matrix> lu;
  if (state.range(1) >= 1) lu.umfpackControl()(UMFPACK_STRATEGY) = UMFPACK_STRATEGY_SYMMETRIC;
  if (state.range(1) == 2) lu.umfpackControl()(UMFPACK_ORDERING) = UMFPACK_ORDERING_METIS;
  lu.analyzePattern(k);
  for (auto _ : state) {
    lu.factorize(k);
    benchmark::DoNotOptimize(lu.info());
  }
  state.counters["unknowns"] = static_cast<double>(k.rows());
}
BENCHMARK(BM_Umfpack)->Args({0, 0})->Args({0, 1})->Args({0, 2})->Args({1, 0})->Args({1, 1})->Args({1, 2})->Args({2, 1})->Unit(benchmark::kMillisecond);

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

}  // namespace
