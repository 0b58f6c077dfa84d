// The stress phase: every particle's material update with its strain increment (or, after the
// fused USL transfer, only the particles it deferred). Elastic and intact points far from onset
// take the closed form (stress_update.hpp); enriched points call updateIntact / updateCracked on
// the side array of band states; failed updates are retried with 2, 4, ... sub-steps.
#include <omp.h>

#include <algorithm>
#include <limits>
#include <optional>
#include <sstream>

#include "mpm/solver.hpp"
#include "mpm/stress_update.hpp"

namespace ecm::mpm {

namespace {

// Bands opened in this step, added to the side arrays after the parallel loop.
struct Onset {
  std::size_t particle;
  std::optional<BandState> first, second;
};

struct Failure {
  std::size_t particle = std::numeric_limits<std::size_t>::max();
  UpdateResult result;
  std::string what;  // an exception from the material (e.g. H <= h at onset)
};

// One update of an enriched point from its bands (nullptr: not opened yet); new bands go to
// `onset` / `secondOnset`. Without the second-band option the point has at most one band.
UpdateResult updateOnce(const TwoPhasePoint& m, Voigt& strain, BandState* band, BandState* second, const Voigt& d,
                        const EffectiveSize& size, std::optional<BandState>& onset, std::optional<BandState>& secondOnset,
                        UpdateOptions options) {
  if (!m.opensSecondBand())
    return band ? m.updateCracked(*band, strain, d, options) : m.updateIntact(strain, d, size, onset, options);
  return band ? m.updateCracked(*band, second, strain, d, size, secondOnset, options)
              : m.updateIntact(strain, d, size, onset, secondOnset, options);
}

// One enriched point: the increment in one go, else in 2^level equal sub-steps.
UpdateResult updateEnriched(const TwoPhasePoint& m, Voigt& strain, BandState* band, BandState* second, const Voigt& d,
                            const EffectiveSize& size, Onset& opened, int levels, UpdateOptions options, long& retries) {
  UpdateResult r = updateOnce(m, strain, band, second, d, size, opened.first, opened.second, options);
  if (r.converged()) return r;
  ++retries;
  for (int level = 1; level <= levels; ++level) {
    const int n = 1 << level;
    const Voigt sub = d / n;
    Voigt s = strain;
    std::optional<BandState> b, b2;
    if (band) b = *band;
    if (second) b2 = *second;
    double dissipation = 0.0;
    bool ok = true, released = false;
    for (int i = 0; i < n && ok; ++i) {
      std::optional<BandState> newFirst, newSecond;
      r = updateOnce(m, s, b ? &*b : nullptr, b2 ? &*b2 : nullptr, sub, size, newFirst, newSecond, options);
      if (newFirst) b = newFirst;
      if (newSecond) b2 = newSecond;
      ok = r.converged();
      dissipation += r.dissipation;
      released = released || r.released;
    }
    if (!ok) continue;
    strain = s;
    if (band)
      *band = *b;
    else
      opened.first = b;
    if (second)
      *second = *b2;
    else
      opened.second = b2;
    r.dissipation = dissipation;
    r.released = released;
    return r;
  }
  return r;
}

}  // namespace

void Solver::updateStresses(bool deferredOnly) {
  if (!deferredOnly) gridHoldsState_ = false;  // every stress may change (the deferred ones scatter after)
  Particles& p = particles_;
  // Positions j = 0 .. count - 1 in the list of particles to update (all, or the deferred ones).
  const std::size_t count = deferredOnly ? deferred_.size() : p.size();
  const std::uint32_t* list = deferredOnly ? deferred_.data() : nullptr;
  const int levels = scene_.solver.substepLevels;
  // Dissipation summed per chunk in particle order (a local sum, stored once: a shared
  // per-particle accumulator put two threads on one cache line and cost half the step), then
  // over the chunks in order: the same bits for any thread count and schedule.
  // Deferred points are the expensive ones (cracked, near onset): smaller chunks balance them.
  const std::size_t kChunk = deferredOnly ? 64 : 512;
  const std::size_t chunks = (count + kChunk - 1) / kChunk;
  std::vector<double> chunkDissipation(chunks, 0.0);
  long retries = 0, released = 0;
  const UpdateOptions options{scene_.solver.snapBack, false};  // explicit: no tangent needed
  Failure failure;
  std::vector<std::vector<Onset>> onsets(static_cast<std::size_t>(threads_));
#pragma omp parallel num_threads(threads_) reduction(+ : retries, released)
  {
    std::vector<Onset>& mine = onsets[static_cast<std::size_t>(omp_get_thread_num())];
    // Dynamic: cracked points cost ~100 intact ones and cluster in space. Each point's update
    // is independent of the others, so the schedule does not change any result.
#pragma omp for schedule(dynamic, 1) nowait
    for (std::size_t c = 0; c < chunks; ++c) {
      double chunkSum = 0.0;
      const std::size_t end = std::min(count, (c + 1) * kChunk);
      for (std::size_t j = c * kChunk; j < end; ++j) {
        const std::size_t i = list ? list[j] : j;
        const MaterialKernel& k = kernels_[p.material[i]];
        const Voigt& d = p.strainIncrement[i];
        // (the fused USL pass has tried the closed form on its deferred points already)
        if (!deferredOnly && closedFormStress(k, d, p.band[i], p.strain[i], p.stress[i])) continue;
        UpdateResult r;
        std::string what;
        switch (k.kind) {
          case ModelKind::LinearElastic:  // a non-finite stress (closedFormStress refused it): reported below
            p.strain[i] += d;
            p.stress[i] = k.stiffness * p.strain[i];
            break;
          case ModelKind::SmearedCrack: {
            SmearedCrack::State s{p.strain[i], p.integrity[i]};
            r = k.smeared->update(s, d);
            p.strain[i] = s.strain;
            p.integrity[i] = s.integrity;
            p.stress[i] = r.stress;
            chunkSum += r.dissipation * p.volume[i];
            break;
          }
          case ModelKind::Enriched: {
            const std::int32_t bi = p.band[i];
            const std::int32_t b2 = p.secondBand.empty() ? -1 : p.secondBand[i];
            Onset onset{i, std::nullopt, std::nullopt};
            try {
              r = updateEnriched(*k.enriched, p.strain[i], bi >= 0 ? &p.bands[static_cast<std::size_t>(bi)] : nullptr,
                                 b2 >= 0 ? &p.secondBands[static_cast<std::size_t>(b2)] : nullptr, d, size_, onset,
                                 levels, options, retries);
            } catch (const std::exception& ex) {
              r.status = UpdateStatus::NotConverged;
              what = ex.what();
            }
            if (r.converged()) {
              p.stress[i] = r.stress;
              if (r.dissipation != 0.0) chunkSum += r.dissipation * p.volume[i];
              released += r.released ? 1 : 0;
              if (onset.first || onset.second) mine.push_back(onset);
            }
            break;
          }
        }
        if (!r.converged() || !p.stress[i].allFinite()) {
#pragma omp critical(ecm_mpm_failure)
          if (i < failure.particle) {
            failure.particle = i;
            failure.result = r;
            failure.what = what;
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
    if (o.first) {
      p.band[o.particle] = static_cast<std::int32_t>(p.bands.size());
      p.bands.push_back(*o.first);
    }
    if (o.second) {
      p.secondBand[o.particle] = static_cast<std::int32_t>(p.secondBands.size());
      p.secondBands.push_back(*o.second);
    }
  }
  // Every 64 steps the bands go back into particle order (decided from the state and the step
  // alone, so a restarted run stores them exactly as an uninterrupted one).
  if ((step_ + 1) % 64 == 0 && !p.bandsInParticleOrder()) p.sortBandsByParticle();
  double dissipated = 0.0;
  for (const double d : chunkDissipation) dissipated += d;
  dissipated_ += dissipated;
  substepped_ += retries;
  released_ += released;
  if (failure.particle != std::numeric_limits<std::size_t>::max()) {
    const std::size_t i = failure.particle;
    std::ostringstream msg;
    msg << "step " << step_ + 1 << ": particle " << i << " at (" << p.position[i][0] << ", " << p.position[i][1]
        << ") mm: ";
    FailureKind kind = FailureKind::MaterialFailure;
    if (failure.result.converged()) {
      kind = FailureKind::NotFinite;
      msg << "non-finite stress";
    } else {
      msg << "material update " << toString(failure.result.status) << " after " << (1 << levels)
          << " sub-steps, residual " << failure.result.residual << " MPa";
      if (!failure.what.empty()) msg << " (" << failure.what << ")";
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
    throw SimulationError(kind, step_ + 1, i, p.position[i], msg.str(), failure.result.status, failure.result.residual);
  }
}

}  // namespace ecm::mpm
