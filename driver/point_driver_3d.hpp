#pragma once
// ecm-point in 3D (`hypothesis: three_dimensional`): one Material3D point along a path whose six
// components (eps_xx, eps_yy, eps_zz, gamma_yz, gamma_xz, gamma_xy | sig_...) are each strain-
// or stress-controlled. Mixed control by Newton on the stress-controlled strains with the
// consistent tangent (Eq. (10)); an intact point steps exactly to onset first; a failing
// increment is halved, up to 2^substep_levels pieces. No opening control in 3D: a snap-back is
// released at the increment's strain (snap_back: release) or stops the run (stop).
#include <array>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "driver/load_path.hpp"
#include "io/yaml_input.hpp"
#include "material/material_3d.hpp"

namespace ecm::driver {

struct Segment3 {
  std::array<Control, 6> control{Control::Strain, Control::Strain, Control::Strain,
                                 Control::Strain, Control::Strain, Control::Strain};
  Voigt6 target = Voigt6::Zero();  // strain (engineering shears) or stress (MPa) at the segment end
  int increments = 1;
};

struct PointScene3 {
  std::string name;
  MaterialParams material;      // hypothesis ThreeDimensional
  double effectiveSize = 0.0;   // H (mm)
  std::vector<Segment3> path;
  SnapBackPolicy snapBack = kDefaultSnapBack;
  double relativeTolerance = 1e-8;  // stress control residual <= this * f_t' (or * 1 MPa if elastic)
  int substepLevels = 10;
};

struct HistoryRow3 {
  int increment = 0;
  int segment = 0;
  Voigt6 strain = Voigt6::Zero();
  Voigt6 stress = Voigt6::Zero();
  double damage = 0.0;
  double integrity = 1.0;
  Vec3 crackNormal = Vec3::Zero();
  double normalJump = 0.0;   // [u].n (mm)
  double slidingJump = 0.0;  // |[u] - ([u].n) n| (mm)
  double volumeFraction = 0.0;
  double work = 0.0;         // int sigma : d eps per unit volume (MPa)
  double dissipation = 0.0;  // accumulated, per unit volume (MPa)
  double storedEnergy = 0.0; // per unit volume (MPa)
  int iterations = 0;
  int substeps = 1;
  bool snapBackRelease = false;
  bool onset = false;        // the exact onset of cracking (a row of its own)
};

struct PointRun3 {
  std::vector<HistoryRow3> history;
  bool completed = false;
  std::string failure;
};

// Whether a point scene file asks for the 3D point (its own or its material's hypothesis).
bool isThreeDimensionalScene(const io::YamlMap& map);
PointScene3 readPointScene3(const io::YamlMap& map);
// A scene's `path` (segments or a preset), shared with the UMAT scene (driver/umat_driver.hpp).
std::vector<Segment3> readPath3(const io::YamlMap& path);
PointScene3 loadPointScene3(const std::filesystem::path& file);

// Presets (strains are totals): uniaxial_tension (sig = 0 but sig_xx), triaxial (eps_xx to
// `strain`, sig_yy = sig_zz = `confinement`, shears stress-free), rotated_axis (uniaxial strain
// `strain` along the unit `direction`).
std::vector<Segment3> presetSegments3(const std::string& name, double strain, int increments, double confinement,
                                      const Vec3& direction);

using RowObserver3 = std::function<void(const HistoryRow3&, int done, int total)>;
PointRun3 runPoint3D(const PointScene3& scene, const RowObserver3& observe = {});
int totalIncrements(const PointScene3& scene);

// history.csv, summary.json, stress_strain.png and traction_opening.png.
void writePointOutputs3(const PointScene3& scene, const PointRun3& run, const std::filesystem::path& dir);

}  // namespace ecm::driver
