#pragma once
// ecm-point --umat LIB.so: a UMAT of any origin (ecm's libecm_umat.so or another Abaqus-interface
// UMAT) driven along the 3D point's paths, as MTest drives one: each increment's stress-
// controlled strains found by Newton with the UMAT's DDSDDE, the state (STRESS, STATEV, SSE,
// SPD, SCD) committed when they converge; an increment whose call asks for less (PNEWDT < 1),
// gives a number that is not one, or does not converge is halved, up to 2^substep_levels pieces.
// Components in ecm's order (xx, yy, zz, yz, xz, xy; engineering shears) in the scene and the
// outputs, Abaqus's (11, 22, 33, 12, 13, 23) at the call. Units: mm, N, MPa.
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "driver/point_driver_3d.hpp"
#include "driver/umat_library.hpp"
#include "io/yaml_input.hpp"

namespace ecm::driver {

struct UmatScene {
  std::string name;
  std::vector<double> props;            // PROPS (NPROPS = their count)
  std::vector<double> initialState;     // STATEV at the start (NSTATV = their count)
  double characteristicLength = 0.0;    // CELENT (mm)
  std::string materialName = "UMAT";    // CMNAME
  std::vector<Segment3> path;
  double stressTolerance = 1e-6;        // MPa: the stress-controlled components' residual
  int substepLevels = 10;
  std::string propsSource = "the scene";  // where PROPS came from (the summary says)
};

struct UmatRow {
  int increment = 0;
  int segment = 0;
  Voigt6 strain = Voigt6::Zero();
  Voigt6 stress = Voigt6::Zero();
  std::vector<double> state;            // STATEV
  double sse = 0.0, spd = 0.0, scd = 0.0;  // as the UMAT returned them (MPa)
  double work = 0.0;                    // int sigma : d eps per unit volume, trapezoidal (MPa)
  int iterations = 0;
  int substeps = 1;
};

struct UmatRun {
  std::vector<UmatRow> history;
  bool completed = false;
  std::string failure;
};

// The scene of a `umat:` block (PROPS, NSTATV, ...) and the 3D point's path keys.
bool isUmatScene(const io::YamlMap& map);
UmatScene readUmatScene(const io::YamlMap& map);
// ecm's UMAT for an ecm 3D point scene: PROPS from its material, H and snap-back policy in
// ecm's layout (umat/umat_props.hpp), STATEV(2) = 1, CELENT = H, the same tolerance in MPa.
UmatScene umatSceneFor(const PointScene3& scene);

using UmatObserver = std::function<void(const UmatRow&, int done, int total)>;
UmatRun runUmat(const UmatScene& scene, const UmatLibrary& library, const UmatObserver& observe = {});

// history.csv written row by row as the run goes (a UMAT that ends the process leaves every
// row before it), then summary.json and stress_strain.png.
class UmatOutputs {
 public:
  UmatOutputs(const UmatScene& scene, const std::filesystem::path& dir);
  ~UmatOutputs();
  void row(const UmatRow& r);
  void finish(const UmatRun& run, const UmatLibrary& library);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace ecm::driver
