#pragma once
// The band law's own envelope as a table law: (0, f_t'), then updateBand's monotonic traction on
// `rows` openings from its elastic limit delta_e = h f_t' / E to `end`, refined towards the steep
// start (delta_e + (end - delta_e) (k / rows)^2; the band law softens at -E_p / h there). The first
// row past delta_e lies so close to it that K0 w = E w / h meets the table where the band law
// leaves its elastic line.
#include <string>

#include "cohesive/band_interface.hpp"
#include "cohesive/table_interface.hpp"

namespace ecm::cohesive::test {

inline TableInterface bandEnvelopeTable(const BandInterface& band, int rows = 20000, double end = 0.5) {
  const double e = band.law.youngsModulus, h = band.bandWidth, ft = band.law.tensileStrength;
  const double onset = h * ft / e;
  TableInterface t;
  t.initialStiffness = e / h;
  t.source = "band-envelope.csv";
  t.opening.push_back(0.0);
  t.traction.push_back(ft);
  BandState s;
  for (int k = 1; k <= rows; ++k) {
    const double z = static_cast<double>(k) / rows, w = onset + (end - onset) * z * z;
    t.opening.push_back(w);
    t.traction.push_back(updateBand(band, s, w).traction);
  }
  return t;
}

}  // namespace ecm::cohesive::test
