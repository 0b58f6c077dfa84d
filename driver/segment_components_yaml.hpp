#pragma once
// A path segment's components in a point scene (2D and 3D): each component given exactly once,
// as a strain (its key in `strainKeys`) or as a stress (MPa, its key in `stressKeys`).
#include <array>
#include <cstddef>
#include <string>

#include "driver/load_path.hpp"
#include "io/yaml_input.hpp"

namespace ecm::driver {

template <std::size_t N, class Target>
void readSegmentComponents(const io::YamlMap& m, const std::array<const char*, N>& strainKeys,
                           const std::array<const char*, N>& stressKeys, std::array<Control, N>& control, Target& target) {
  for (std::size_t c = 0; c < N; ++c) {
    const bool strain = m.has(strainKeys[c]), stress = m.has(stressKeys[c]);
    if (strain == stress)
      m.failHere(std::string("give exactly one of '") + strainKeys[c] + "' (strain) or '" + stressKeys[c] + "' (stress, MPa)");
    control[c] = strain ? Control::Strain : Control::Stress;
    target[static_cast<Eigen::Index>(c)] = m.get<double>(strain ? strainKeys[c] : stressKeys[c], io::Range::any());
  }
}

}  // namespace ecm::driver
