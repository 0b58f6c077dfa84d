// What this machine's memory gives one and two threads: a STREAM-like triad c = a + 1.5 b over
// three arrays of doubles, at sizes that live in DRAM, L3 and L2 (docs/performance.md, "What
// this machine can give a second thread"). The explicit MPM pass is bound by memory traffic, so
// its speed-up on two threads is bounded by this one's, not by the compute ceiling of 2.
#include <benchmark/benchmark.h>
#include <omp.h>

#include <cstddef>
#include <vector>

namespace {

void BM_StreamTriad(benchmark::State& state) {
  const auto n = static_cast<std::ptrdiff_t>(state.range(0)) * 1024 / 8;  // kB per array
  const int threads = static_cast<int>(state.range(1));
  std::vector<double> a(static_cast<std::size_t>(n), 1.0), b(static_cast<std::size_t>(n), 2.0), c(static_cast<std::size_t>(n), 0.0);
  for (auto _ : state) {
#pragma omp parallel for num_threads(threads) schedule(static)
    for (std::ptrdiff_t i = 0; i < n; ++i) c[static_cast<std::size_t>(i)] = a[static_cast<std::size_t>(i)] + 1.5 * b[static_cast<std::size_t>(i)];
    benchmark::DoNotOptimize(c.data());
    benchmark::ClobberMemory();
  }
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations()) * 3 * n * static_cast<std::int64_t>(sizeof(double)));
}
BENCHMARK(BM_StreamTriad)
    ->ArgsProduct({{160 * 1024, 8 * 1024, 300}, {1, 2}})
    ->ArgNames({"kB", "threads"})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

}  // namespace


