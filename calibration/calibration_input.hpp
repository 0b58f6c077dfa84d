#pragma once
// What ecm-calibrate is asked to do, from the command line and/or a YAML input file, and the
// checked plan derived from it. Every quantity has one YAML key and one command-line flag:
//
//   youngs_modulus        --E          E (MPa)
//   poisson_ratio         --nu         nu (-), only for --write-material
//   tensile_strength      --ft         f_t' (MPa)
//   fracture_energy       --GF         G_F (N/mm)
//   band_width            --h          h (mm)
//   softening_exponent    --n          n (-), 0 < n < 0.5
//   softening_modulus     --Ep         E_p (MPa), forward mode only
//   smeared_element_size  --smeared-H  H (mm), crack-band calibration
//   density               --density    t/mm^3, only for --write-material
//   fit: hordijk          --fit hordijk
//   fit_csv: FILE         --fit-csv FILE   (in YAML: relative to the YAML file's folder)
//   out: DIR              --out DIR        (default out/calibrate)
//   write_material: FILE  --write-material FILE
//   name, hypothesis      --name, --hypothesis  (of the written material)
//
// Modes: G_F and n -> solve E_p; G_F and a fit target -> fit n and E_p; E_p and n without G_F
// -> forward (G_F); G_F, n and H -> crack band. Command-line values override the YAML file.
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "calibration/target_curve.hpp"
#include "io/yaml_input.hpp"
#include "material/damage_function.hpp"
#include "material/linear_elastic.hpp"
#include "umat/umat_props.hpp"

namespace ecm::calibration {

enum class CalibrationMode { Forward, SolveSofteningModulus, Fit, CrackBand };
const char* toString(CalibrationMode m);

struct CalibrationInput {
  std::optional<double> youngsModulus, poissonRatio, tensileStrength, fractureEnergy, bandWidth, softeningExponent,
      softeningModulus, smearedSize, density;
  std::optional<std::string> fit;  // "hordijk"
  std::optional<std::filesystem::path> fitCsv, out, writeMaterial, writeUmat;
  std::optional<std::vector<double>> elementSizes;  // H (mm) per element size, for the UMAT card
  std::optional<std::string> umatDialect;           // "calculix" | "abaqus"
  std::optional<TargetCurve> fitPoints;  // measured points given in code (the Python module), as fit_csv
  std::optional<std::string> name, hypothesis;
  // Where values read from a YAML file came from: key -> (file, line), for messages.
  std::map<std::string, std::pair<std::string, int>> origin;
};

// One numeric quantity: its YAML key, command-line flag, symbol, unit and allowed range.
struct Quantity {
  const char* key;
  const char* flag;
  const char* symbol;
  const char* unit;
  std::optional<double> CalibrationInput::*member;
  io::Range range;
  const char* rangeNote;  // why the range is what it is ("" if obvious)
};
const std::vector<Quantity>& quantities();

// Reads the YAML input (validated with the io reader: unknown keys, types; ranges are checked by
// planCalibration with FILE:LINE of the offending key).
CalibrationInput readCalibrationInput(const std::filesystem::path& path);
CalibrationInput readCalibrationInput(const io::YamlMap& map);
// Values set in `top` replace those of `base` (command line over input file).
void overlay(CalibrationInput& base, const CalibrationInput& top);

struct CalibrationPlan {
  CalibrationMode mode = CalibrationMode::SolveSofteningModulus;
  DamageLawParams law;          // E, f_t' and whichever of E_p, n are given
  double width = 0.0;           // h, or H for the crack band
  double fractureEnergy = 0.0;  // target G_F (0 in forward mode)
  std::optional<TargetCurve> target;
  std::filesystem::path out = "out/calibrate";
  std::optional<std::filesystem::path> writeMaterial;
  // The UMAT card (umat/umat_props.hpp): one *MATERIAL per element size H.
  std::optional<std::filesystem::path> writeUmat;
  std::vector<double> elementSizes;
  umat::Dialect dialect = umat::Dialect::CalculiX;
  // For the written material and card.
  std::string name = "calibrated";
  Hypothesis hypothesis = Hypothesis::PlaneStress;
  double poissonRatio = 0.0;
  double density = 0.0;
};

// Chooses the mode and checks every value: missing, conflicting, non-finite or out-of-range
// quantities and G_F below the elastic minimum are rejected naming the value and the bound
// (io::InputError "FILE:LINE: ..." for values from the YAML file, CalibrationError otherwise).
CalibrationPlan planCalibration(const CalibrationInput& in);

}  // namespace ecm::calibration
