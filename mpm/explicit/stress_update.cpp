// The stress phase: every particle's material update with its strain increment (or, after the
// fused USL transfer, only the particles it deferred). Elastic and intact points far from onset
// take the closed form (Material::closedFormStress); the others take Material::update on a view
// of the particle's arrays (band states in side arrays), which also sub-steps failed updates.
#include <omp.h>

#include <algorithm>
#include <limits>
#include <optional>
#include <sstream>

#include "mpm/core/errors.hpp"
#include "mpm/explicit/phases.hpp"
#include "mpm/setup/stress_direction.hpp"

namespace ecm::mpm {

namespace {

// Bands opened in this step, added to the side arrays after the parallel loop.
struct Onset {
  std::size_t particle;
  OpenedBands bands;
};

struct Failure {
  std::size_t particle = std::numeric_limits<std::size_t>::max();
  UpdateResult result;
};

}  // namespace

void storeStressesOfIntactPoints(const StepSetup& setup, Particles& p) {
  const auto n = static_cast<std::ptrdiff_t>(p.size());
#pragma omp parallel for num_threads(setup.threads) schedule(static)
  for (std::ptrdiff_t k = 0; k < n; ++k) {
    const auto i = static_cast<std::size_t>(k);
    const Material& m = setup.materials[p.material[i]];
    if (m.stressFollowsStrain(p.band[i] >= 0)) p.stress[i] = m.intactStress(p.strain[i]);
  }
}

void updateStresses(const StepSetup& setup, long step, Particles& p, RunTotals& totals, CrackPaths& paths,
                    const std::vector<std::uint32_t>* only) {
  const bool deferredOnly = only != nullptr;
  // Positions j = 0 .. count - 1 in the list of particles to update (all, or the deferred ones).
  const std::size_t count = deferredOnly ? only->size() : p.size();
  const std::uint32_t* list = deferredOnly ? only->data() : nullptr;
  // Dissipation summed per chunk in particle order (a local sum, stored once: a shared
  // per-particle accumulator put two threads on one cache line and cost half the step), then
  // over the chunks in order: the same bits for any thread count and schedule.
  // Deferred points are the expensive ones (cracked, near onset): smaller chunks balance them.
  const std::size_t kChunk = deferredOnly ? 64 : 512;
  const std::size_t chunks = (count + kChunk - 1) / kChunk;
  std::vector<double> chunkDissipation(chunks, 0.0);
  long retries = 0, released = 0;
  UpdateOptions options{setup.scene.solver.snapBack, false};  // explicit: no tangent needed
  options.substepLevels = setup.scene.solver.substepLevels;
  Failure failure;
  // The secant responses of the bands (docs/model.md); new entries are built at their first update.
  const bool keepSecants = p.keepsSecants();
  p.secants.resize(keepSecants ? p.bands.size() : 0);
  std::vector<std::vector<Onset>> onsets(static_cast<std::size_t>(setup.threads));
  const bool tracked = paths.tracked();
  std::vector<std::vector<OnsetCandidate>> held(static_cast<std::size_t>(setup.threads));
#pragma omp parallel num_threads(setup.threads) reduction(+ : retries, released)
  {
    std::vector<Onset>& mine = onsets[static_cast<std::size_t>(omp_get_thread_num())];
    std::vector<OnsetCandidate>& mineHeld = held[static_cast<std::size_t>(omp_get_thread_num())];
    // Dynamic: cracked points cost ~100 intact ones and cluster in space. Each point's update
    // is independent of the others, so the schedule does not change any result.
#pragma omp for schedule(dynamic, 1) nowait
    for (std::size_t c = 0; c < chunks; ++c) {
      double chunkSum = 0.0;
      const std::size_t end = std::min(count, (c + 1) * kChunk);
      for (std::size_t j = c * kChunk; j < end; ++j) {
        const std::size_t i = list ? list[j] : j;
        const Material& m = setup.materials[p.material[i]];
        const Voigt& d = p.strainIncrement[i];
        const std::int32_t bi = p.band[i];
        // (the fused USL pass has tried the closed form on its deferred points already)
        if (!deferredOnly && m.closedFormStress(d, bi >= 0, p.strain[i], p.stress[i])) continue;
        const std::int32_t b2 = p.secondBand.empty() ? -1 : p.secondBand[i];
        Onset onset{i, {}};
        const auto k = static_cast<std::size_t>(bi);
        // Tracked crack paths: an intact enriched point reaching onset opens its band only on a
        // path, with the path's normal; elsewhere it stays intact (docs/model.md, "Crack paths").
        UpdateOptions pointOptions = options;
        Vec2 pathNormal;
        EffectiveSize pathSize = setup.size;
        if (tracked && bi < 0 && m.enriched()) {
          if (const std::optional<PathCrossing> n = paths.crossingAt(p.position[i])) {
            pathNormal = n->normal;
            pathSize = EffectiveSize::fixed(n->effectiveSize);
            pointOptions.onsetNormal = &pathNormal;
          } else {
            p.strain[i] += d;
            p.stress[i] = m.intactStress(p.strain[i]);
            const TwoPhasePoint& e = *m.enriched();
            const double y = e.intactDrivingForce(p.strain[i]);
            if (y >= e.bandLaw().onsetDrivingForce() && p.stress[i].allFinite()) {
              const double overstress = std::sqrt(y / e.bandLaw().onsetDrivingForce());
              mineHeld.push_back({i, p.position[i], overstress, p.stress[i] / overstress});
            }
            if (!p.stress[i].allFinite()) {
#pragma omp critical(ecm_mpm_failure)
              if (i < failure.particle) {
                failure.particle = i;
                failure.result = UpdateResult{};
              }
            }
            continue;
          }
        }
        const UpdateResult r = m.update({p.strain[i], p.integrity.empty() ? nullptr : &p.integrity[i],
                                         bi >= 0 ? &p.bands[k] : nullptr,
                                         b2 >= 0 ? &p.secondBands[static_cast<std::size_t>(b2)] : nullptr,
                                         bi >= 0 && keepSecants ? &p.secants[k] : nullptr},
                                        d, pathSize, onset.bands, pointOptions);
        if (r.converged()) {
          p.stress[i] = r.stress;
          if (r.dissipation != 0.0) chunkSum += r.dissipation * p.volume[i];
          released += r.released ? 1 : 0;
          retries += r.substeps > 1 ? 1 : 0;
          if (onset.bands.any()) mine.push_back(onset);
        }
        if (!r.converged() || !p.stress[i].allFinite()) {
#pragma omp critical(ecm_mpm_failure)
          if (i < failure.particle) {
            failure.particle = i;
            failure.result = r;
          }
        }
      }
      chunkDissipation[c] = chunkSum;
    }
  }
  // New bands in particle order, so that indices do not depend on the thread count.
  std::vector<Onset> all;
  for (auto& o : onsets) all.insert(all.end(), o.begin(), o.end());
  std::sort(all.begin(), all.end(), [](const Onset& a, const Onset& b) { return a.particle < b.particle; });
  for (const Onset& o : all) {
    if (o.bands.first) {
      p.band[o.particle] = static_cast<std::int32_t>(p.bands.size());
      p.bands.push_back(*o.bands.first);
    }
    if (o.bands.second) {
      p.secondBand[o.particle] = static_cast<std::int32_t>(p.secondBands.size());
      p.secondBands.push_back(*o.bands.second);
    }
  }
  p.secants.resize(keepSecants ? p.bands.size() : 0);  // (so that the sort below moves them with their bands)
  if (tracked) {  // the paths grow from this step's new bands and held points, in particle order
    std::vector<OnsetCandidate> candidates;
    for (auto& h : held) candidates.insert(candidates.end(), h.begin(), h.end());
    paths.noteHeld(candidates);
    std::vector<Vec2> opened;
    for (const Onset& o : all)
      if (o.bands.first) opened.push_back(p.position[o.particle]);
    if (!candidates.empty() || !opened.empty()) {
      std::sort(candidates.begin(), candidates.end(),
                [](const OnsetCandidate& a, const OnsetCandidate& b) { return a.particle < b.particle; });
      paths.grow(opened, std::move(candidates), intactStressAverage(setup.materials, p));
    }
  }
  // Every 64 steps the bands go back into particle order (decided from the state and the step
  // alone, so a restarted run stores them exactly as an uninterrupted one).
  if ((step + 1) % 64 == 0 && !p.bandsInParticleOrder()) p.sortBandsByParticle();
  double dissipated = 0.0;
  for (const double d : chunkDissipation) dissipated += d;
  totals.dissipated += dissipated;
  totals.substepped += retries;
  totals.released += released;
  if (failure.particle != std::numeric_limits<std::size_t>::max()) {
    const std::size_t i = failure.particle;
    std::ostringstream msg;
    msg << "step " << step + 1 << ": particle " << i << " at (" << p.position[i][0] << ", " << p.position[i][1]
        << ") mm: ";
    FailureKind kind = FailureKind::MaterialFailure;
    if (failure.result.converged()) {
      kind = FailureKind::NotFinite;
      msg << "non-finite stress";
    } else {
      if (failure.result.status == UpdateStatus::SnapBack) kind = FailureKind::SnapBack;
      msg << setup.materials[p.material[i]].explain(failure.result);
      // The full state, to reproduce the update outside the run (material/two_phase_point.hpp).
      msg.precision(17);
      const auto v = [&](const auto& x) {
        std::ostringstream o;
        o.precision(17);
        o << "[" << x[0];
        for (Eigen::Index c = 1; c < x.size(); ++c) o << ", " << x[c];
        return o.str() + "]";
      };
      msg << "; state: strain " << v(p.strain[i]) << ", increment " << v(p.strainIncrement[i]);
      if (p.band[i] >= 0) {
        const BandState& b = p.bands[static_cast<std::size_t>(p.band[i])];
        msg << ", band {normal " << v(b.crackNormal) << ", jump " << v(b.jump) << ", onset_strain " << v(b.onsetStrain)
            << ", integrity " << b.integrity << ", f " << b.volumeFraction << "}";
      }
      if (const BandState* b = p.secondBandOf(i))
        msg << ", second band {normal " << v(b->crackNormal) << ", jump " << v(b->jump) << ", onset_strain "
            << v(b->onsetStrain) << ", integrity " << b->integrity << ", f " << b->volumeFraction << "}";
    }
    throw SimulationError(kind, step + 1, i, p.position[i], msg.str(), failure.result.status, failure.result.residual);
  }
}

}  // namespace ecm::mpm
