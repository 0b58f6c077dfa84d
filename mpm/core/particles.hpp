#pragma once
// Material points, one array per field (structure of arrays, fixed-size Eigen types, no
// per-particle heap). A cracked enriched point refers to its band state in a side array that
// grows only when points crack.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "material/material.hpp"
#include "material/two_phase_point.hpp"
#include "mpm/core/shape_function.hpp"

namespace ecm::mpm {

struct Particles {
  std::vector<Vec2> position;        // mm
  std::vector<Vec2> origin;          // mm, where the point was seeded (displacement = position - origin:
                                     // not stored, one array less to stream through every step)
  std::vector<Vec2> velocity;        // mm/s
  std::vector<double> mass;          // t
  std::vector<double> volume;        // mm^3 (initial; small strain)
  std::vector<Voigt> strain;         // engineering shear
  std::vector<Voigt> stress;         // MPa (an intact point's: stored when the explicit solver's particles
                                     // are read, docs/model.md "An intact point's stress")
  std::vector<Voigt> strainIncrement;// of the current step
  std::vector<std::uint8_t> material;// index into the scene's materials
  std::vector<std::int32_t> band;    // index into `bands`, -1 while intact (enriched)
  std::vector<double> integrity;     // smeared crack only (empty if no smeared material)
  // Where this step's shape functions sit (first node and offsets), located at the step's first
  // particle-to-grid transfer; the weights are expanded from it where they are used (24 bytes
  // instead of a stored stencil's 104; MUSL's second transfer needs the step-start weights).
  std::vector<StencilAt> stencilAt;

  std::vector<BandState> bands;      // side array: one per cracked enriched point
  // The secant response of each band (its unloading update as affine maps, docs/model.md): a
  // cache, rebuilt wherever it is not its band's, so it is neither checkpointed nor kept in step
  // by whoever adds bands (the explicit stress phase sizes it; empty under the second-band option).
  std::vector<SecantResponse> secants;
  // The second band (second_band: orthogonal, docs/model.md): an index per particle into
  // `secondBands` (-1: none), allocated only when a material of the scene has the option.
  std::vector<std::int32_t> secondBand;
  std::vector<BandState> secondBands;

  std::size_t size() const { return position.size(); }
  // 0 intact .. 1 fully damaged: the band's damage (enriched), 1 - integrity (smeared crack).
  double damage(std::size_t i) const {
    if (band[i] >= 0) return bands[static_cast<std::size_t>(band[i])].damage();
    return integrity.empty() ? 0.0 : 1.0 - integrity[i];
  }
  Vec2 displacement(std::size_t i) const { return position[i] - origin[i]; }  // mm, since the start
  void resize(std::size_t n, bool withIntegrity, bool withSecondBand = false);
  const BandState* secondBandOf(std::size_t i) const {
    return !secondBand.empty() && secondBand[i] >= 0 ? &secondBands[static_cast<std::size_t>(secondBand[i])] : nullptr;
  }
  std::size_t twoBandPoints() const { return secondBands.size(); }

  // Bands are appended in the order points crack; the stress update reads them in particle
  // order. Stored in particle order, that read is sequential instead of scattered (the cracked
  // update waits on memory otherwise). Reordering changes no value, only where a band is stored.
  bool bandsInParticleOrder() const;
  void sortBandsByParticle();

  // Memory per particle of the arrays above (bytes), intact and cracked.
  std::size_t bytesPerParticle() const;
  // Whether the explicit stress phase keeps the bands' secant responses: while no material may
  // open a second band (that update takes the predictor's solve; secondBand is empty then).
  bool keepsSecants() const { return secondBand.empty(); }
  // Added when a point cracks: its band state, and the band's secant response where they are kept.
  std::size_t bytesPerBand() const { return sizeof(BandState) + (keepsSecants() ? sizeof(SecantResponse) : 0); }
};

// The mass and volume that every point of a material shares, bit for bit (seeding gives every
// point the cell's share of volume and mass = density x volume): the fused USL pass reads these
// instead of two per-point arrays, 16 bytes less per point and step (docs/performance.md).
struct SharedMassVolume {
  double mass = 0.0, volume = 0.0;
};
// One per material index below `materials`; empty where the points of some material differ.
std::vector<SharedMassVolume> sharedMassAndVolume(const Particles& p, std::size_t materials);

// The optional per-particle arrays a material needs: the smeared crack's integrity, and the index
// into the second bands when the material has the option (Particles::resize's two flags). The
// one place that decides it: seeding (for the materials its particles use) and the memory
// estimate (for the scene's bodies) both ask here.
struct ParticleFields {
  bool integrity = false;
  bool secondBand = false;
  ParticleFields& operator|=(const ParticleFields& o) {
    integrity = integrity || o.integrity;
    secondBand = secondBand || o.secondBand;
    return *this;
  }
};
ParticleFields fieldsFor(const MaterialParams& material);

}  // namespace ecm::mpm
