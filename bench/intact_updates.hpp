#pragma once
// The intact update's benchmark, for the 2D and the 3D enriched point alike: a batch of points
// that stay intact (most points of a structure, most of the time), each taking one increment and
// its reverse, so the batch stays in place. ns per update.
#include <benchmark/benchmark.h>

#include <cstdint>
#include <optional>
#include <vector>

#include "material/snap_back_policy.hpp"

template <class Point, class Strain, class Size>
void intactUpdates(benchmark::State& st, const Point& model, std::vector<Strain> strains, const Strain& step,
                   const Size& size) {
  std::optional<typename Point::Band> onset;
  for (auto _ : st) {
    for (auto& e : strains) {
      const auto r = model.updateIntact(e, step, size, onset, ecm::SnapBackPolicy::Stop);
      benchmark::DoNotOptimize(r.stress);
      e -= step;
    }
  }
  if (onset) st.SkipWithError("a point cracked");
  st.SetItemsProcessed(st.iterations() * static_cast<std::int64_t>(strains.size()));
}
