#pragma once
// PROPS of ecm's UMAT for a material of ecm's (the inverse of materialFromProps,
// umat/umat_layout.hpp), and the input-deck card that carries them: *MATERIAL, *USER MATERIAL
// with its constants, *DEPVAR (docs/fe-codes.md, "Material cards"). Units: mm, N, MPa.
#include <optional>
#include <string>
#include <vector>

#include "material/material.hpp"

namespace ecm::umat {

// PROPS 1-9 (10 with `substepLevels`) for `material` (enriched or linear elastic) in an element
// of effective size `effectiveSize` (mm; 0: the caller's CELENT). Throws ParameterError for a
// model the UMAT does not carry (smeared crack) or the second band.
std::vector<double> propsFor(const MaterialParams& material, double effectiveSize, SnapBackPolicy snapBack,
                             std::optional<int> substepLevels = std::nullopt);

// The material card for one or more element sizes (one *MATERIAL each, named
// `<name>_H<size>` when there are several), in the dialect of the code that reads it.
enum class Dialect { Abaqus, CalculiX };
struct CardRequest {
  std::string name;                  // the material's name in the deck (letters, digits, '_', '-')
  std::vector<double> effectiveSizes;  // H per element size (mm); {0} asks for CELENT (Abaqus only)
  SnapBackPolicy snapBack = SnapBackPolicy::Release;
  Dialect dialect = Dialect::CalculiX;
  std::string source;                // what produced the constants (one comment line), may be empty
};
// Throws ParameterError naming what cannot be written (a CELENT request for CalculiX, an H at
// or below the band width, a name CalculiX would not pass to a UMAT).
std::string materialCard(const MaterialParams& material, const CardRequest& request);

}  // namespace ecm::umat
