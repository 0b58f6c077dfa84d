// The averaged stress of the crack paths (docs/model.md, "Crack paths").
#include "mpm/setup/stress_direction.hpp"

#include <cmath>

namespace ecm::mpm {

AveragedStress intactStressAverage(const std::vector<Material>& materials, const Particles& particles,
                                   const std::vector<Voigt>* stresses) {
  return [&materials, &particles, stresses](const Vec2& at, double radius, double sharpness) -> std::optional<Voigt> {
    const Particles& p = particles;
    Voigt sum = Voigt::Zero();
    double weight = 0.0;
    const double r2 = radius * radius;
    for (std::size_t i = 0; i < p.size(); ++i) {
      if (p.band[i] >= 0) continue;
      const Vec2 r = p.position[i] - at;
      const double d2 = r.squaredNorm();
      if (d2 >= r2) continue;
      const double q = 1.0 - d2 / r2;
      double w = p.volume[i] * q * q;
      const TwoPhasePoint* e = materials[p.material[i]].enriched();
      if (!e) continue;  // (only points that can crack tell where a crack runs)
      Voigt stress = stresses ? (*stresses)[i] : Voigt(e->stiffness() * p.strain[i]);
      // A point held intact past onset counts with its stress scaled back onto the onset surface:
      // its direction, not a magnitude no material point could carry.
      const double y = e->bandLaw().drivingForceValue(stress), onset = e->bandLaw().onsetDrivingForce();
      if (y > onset) stress *= std::sqrt(onset / y);
      else if (sharpness > 0.0) w *= std::pow(std::max(y, 0.0) / onset, sharpness);
      sum += (w / e->tensileStrength()) * stress;
      weight += w;
    }
    if (weight <= 0.0) return std::nullopt;
    return Voigt(sum / weight);
  };
}

}  // namespace ecm::mpm
