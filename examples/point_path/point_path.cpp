// Uniaxial tension of one enriched material point (the paper's concrete, H = 10 mm) through
// onset and softening, then unloading: prints strain, stress, band damage and dissipation.
// Units: mm, N, MPa.
#include <cstdio>

#include "ecm/version.hpp"
#include "material/material.hpp"

int main() {
  ecm::MaterialParams p;
  p.name = "concrete";
  p.model = ecm::ModelKind::Enriched;
  p.elastic = {32000.0, 0.2, ecm::Hypothesis::PlaneStress};  // E (MPa), nu
  p.tensileStrength = 3.0;                                   // f_t' (MPa)
  p.softeningModulus = 8.184;                                // E_p (MPa), from ecm-calibrate for G_F = 0.11 N/mm
  p.softeningExponent = 0.128;                               // n
  p.bandWidth = 0.05;                                        // h (mm)
  const ecm::Material material(p);  // validates the parameters (ecm::ParameterError)

  ecm::MaterialPoint point;
  const auto size = ecm::EffectiveSize::fixed(10.0);  // H (mm): f = h / H = 0.005
  double dissipated = 0.0;                             // N mm / mm^3
  std::fprintf(stderr, "ecm %s\n", ecm::kVersion);
  std::printf("%12s %12s %10s %12s\n", "eps_xx", "sigma_xx", "damage", "dissipated");
  for (int step = 1; step <= 300; ++step) {
    const double rate = step <= 250 ? 1e-6 : -1e-6;  // load, then unload
    const ecm::Voigt d(rate, -0.2 * rate, 0.0);       // a strain path (sigma_yy is not held at 0 here)
    const ecm::UpdateResult r = material.update(point, d, size);
    if (!r.converged()) {
      std::printf("step %d: %s\n", step, material.explain(r).c_str());
      return 1;
    }
    dissipated += r.dissipation;
    if (step % 25 == 0)
      std::printf("%12.4e %12.5f %10.5f %12.4e\n", point.strain[0], r.stress[0], point.damage(), dissipated);
  }
  return 0;
}
