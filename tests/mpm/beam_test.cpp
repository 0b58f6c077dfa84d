// The notched beam in three-point bending against the cohesive reference, coarse mesh
// (tests/mpm/beam_check.hpp): with tracked crack paths the crack runs on the ligament and behaves
// as a cohesive crack. Measured 2026-12-06: against the point's law, peak +2.1 %, |P - P_ref| at
// most 4.2 % of the peak; against the 1D band law +3.5 % and 4.3 %.
#include "beam_check.hpp"

namespace ecm::mpm::test {
namespace {

TEST(Beam, TheCoarseBeamsCrackRunsOnTheLigamentAsACohesiveCrack) {
  checkBeam("data/validation/beam-coarse-implicit.yaml", 2.5, 0.05);
}

}  // namespace
}  // namespace ecm::mpm::test
