// The notched beam in three-point bending against the cohesive reference, coarse mesh
// (tests/mpm/beam_check.hpp): with tracked crack paths the crack runs on the ligament and behaves
// as a cohesive crack. Measured 2026-12-06: peak +1.8 %, |P - P_ref| at most 3.2 % of the peak.
#include "beam_check.hpp"

namespace ecm::mpm::test {
namespace {

TEST(Beam, TheCoarseBeamsCrackRunsOnTheLigamentAsACohesiveCrack) {
  checkBeam("data/validation/beam-coarse-implicit.yaml", 2.5, 0.05);
}

}  // namespace
}  // namespace ecm::mpm::test
