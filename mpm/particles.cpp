#include "mpm/particles.hpp"

namespace ecm::mpm {

void Particles::resize(std::size_t n, bool withIntegrity) {
  position.resize(n, Vec2::Zero());
  displacement.resize(n, Vec2::Zero());
  velocity.resize(n, Vec2::Zero());
  mass.resize(n, 0.0);
  volume.resize(n, 0.0);
  strain.resize(n, Voigt::Zero());
  stress.resize(n, Voigt::Zero());
  strainIncrement.resize(n, Voigt::Zero());
  material.resize(n, 0);
  band.resize(n, -1);
  integrity.resize(withIntegrity ? n : 0, 1.0);
  stencilAt.resize(n);
}

std::size_t Particles::bytesPerParticle() const {
  std::size_t b = sizeof(Vec2) * 3 + sizeof(double) * 2 + sizeof(Voigt) * 3 + sizeof(std::uint8_t) +
                  sizeof(std::int32_t) + sizeof(StencilAt);
  if (!integrity.empty()) b += sizeof(double);
  return b;
}

}  // namespace ecm::mpm
