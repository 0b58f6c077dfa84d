#include "mpm/core/particles.hpp"

#include <bit>
#include <utility>

namespace ecm::mpm {

void Particles::resize(std::size_t n, bool withIntegrity, bool withSecondBand) {
  position.resize(n, Vec2::Zero());
  origin.resize(n, Vec2::Zero());
  velocity.resize(n, Vec2::Zero());
  mass.resize(n, 0.0);
  volume.resize(n, 0.0);
  strain.resize(n, Voigt::Zero());
  stress.resize(n, Voigt::Zero());
  strainIncrement.resize(n, Voigt::Zero());
  material.resize(n, 0);
  band.resize(n, -1);
  integrity.resize(withIntegrity ? n : 0, 1.0);
  secondBand.resize(withSecondBand ? n : 0, -1);
  stencilAt.resize(n);
}

std::size_t Particles::bytesPerParticle() const {
  std::size_t b = sizeof(Vec2) * 3 + sizeof(double) * 2 + sizeof(Voigt) * 3 + sizeof(std::uint8_t) +
                  sizeof(std::int32_t) + sizeof(StencilAt);
  if (!integrity.empty()) b += sizeof(double);
  if (!secondBand.empty()) b += sizeof(std::int32_t);
  return b;
}

std::vector<SharedMassVolume> sharedMassAndVolume(const Particles& p, std::size_t materials) {
  std::vector<SharedMassVolume> shared(materials);
  std::vector<bool> seen(materials, false);
  const auto same = [](double a, double b) { return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b); };
  for (std::size_t i = 0; i < p.size(); ++i) {
    const std::size_t m = p.material[i];
    if (m >= materials) return {};
    if (!seen[m]) {
      shared[m] = {p.mass[i], p.volume[i]};
      seen[m] = true;
    } else if (!same(shared[m].mass, p.mass[i]) || !same(shared[m].volume, p.volume[i])) {
      return {};
    }
  }
  return shared;
}

namespace {

bool inParticleOrder(const std::vector<std::int32_t>& index) {
  std::int32_t last = -1;
  for (const std::int32_t b : index) {
    if (b < 0) continue;
    if (b != last + 1) return false;
    last = b;
  }
  return true;
}

// The states (and their secant responses, if kept: `secants` of the same size) in particle order.
void sortByParticle(std::vector<std::int32_t>& index, std::vector<BandState>& states,
                    std::vector<SecantResponse>* secants = nullptr) {
  const bool withSecants = secants != nullptr && secants->size() == states.size();
  std::vector<BandState> sorted;
  std::vector<SecantResponse> sortedSecants;
  sorted.reserve(states.size());
  if (withSecants) sortedSecants.reserve(states.size());
  for (std::int32_t& b : index) {
    if (b < 0) continue;
    sorted.push_back(states[static_cast<std::size_t>(b)]);
    if (withSecants) sortedSecants.push_back((*secants)[static_cast<std::size_t>(b)]);
    b = static_cast<std::int32_t>(sorted.size() - 1);
  }
  states = std::move(sorted);
  if (withSecants) *secants = std::move(sortedSecants);
}

}  // namespace

bool Particles::bandsInParticleOrder() const { return inParticleOrder(band) && inParticleOrder(secondBand); }

void Particles::sortBandsByParticle() {
  sortByParticle(band, bands, &secants);
  sortByParticle(secondBand, secondBands);
}

ParticleFields fieldsFor(const MaterialParams& material) {
  return {material.model == ModelKind::SmearedCrack, material.secondBand != SecondBandOption::Off};
}

}  // namespace ecm::mpm
