#pragma once
// The single-point strain-path driver: runs a load path on one material point and records
// every increment. Strain control, mixed strain/stress control, opening control (which traces
// snap-back branches), sub-stepping, and snap-back detection under strain control.
#include <functional>
#include <string>
#include <vector>

#include "driver/load_path.hpp"
#include "driver/mixed_control.hpp"

namespace ecm::driver {

struct PointScene {
  std::string name;
  MaterialParams material;
  double effectiveSize = 0.0;  // H (mm)
  std::vector<Segment> path;
  // At a snap-back of the point: Stop stops at the limit point; Release reports it, finds the
  // stable state at the same strain (opening control) and goes on.
  SnapBackPolicy snapBack = kDefaultSnapBack;
  double relativeTolerance = 1e-8;  // stress control residual <= this * f_t' (or * 1 MPa if elastic)
  int substepLevels = 10;           // a failing increment is retried in 2, 4, ... 2^levels pieces (0: never)
  // The one check of a point scene's values; throws io::ValueError naming the key (runPoint and
  // the YAML reader call it).
  void validate() const;
};

struct HistoryRow {
  int increment = 0;
  int segment = 0;
  Voigt strain = Voigt::Zero();
  Voigt stress = Voigt::Zero();
  double damage = 0.0;
  double integrity = 1.0;    // 1 - D, kept separately (precision near D = 1, docs/model.md pitfall 3)
  double normalJump = 0.0;   // [u].n (mm), enriched only
  double slidingJump = 0.0;  // [u].t (mm)
  double opening = 0.0;      // inelastic opening w (mm): h (eps_L - C sigma)_nn, or H (eps - C sigma)_nn smeared
  Vec2 crackNormal = Vec2::Zero();
  double volumeFraction = 0.0;
  double work = 0.0;         // int sigma : d eps per unit volume (MPa)
  double dissipation = 0.0;  // accumulated, per unit volume (MPa)
  int iterations = 0;
  int substeps = 1;
  bool openingControl = false;
  bool snapBackRelease = false;  // this row is the stable state reached after a snap-back
  unsigned event = 0;         // RowEvent bits: a state inside an increment with a row of its own
  // The second band (second_band: orthogonal), once it has opened.
  bool secondBand = false;
  Vec2 secondNormal = Vec2::Zero();
  double secondDamage = 0.0;
  double secondNormalJump = 0.0;   // [u]_2 . n2 (mm)
  double secondSlidingJump = 0.0;  // [u]_2 . t2 (mm)
};

// Rows of their own inside an increment (the `event` column of history.csv, bits).
enum RowEvent : unsigned {
  kOnsetRow = 1,       // the exact onset of cracking (Eq. (12) with D = 0)
  kLastStableRow = 2,  // the last stable state before a snap-back: the limit point of the path
  kPeakRow = 4,        // a maximum of the first principal stress inside an increment
};

struct SnapBackReport {
  bool detected = false;
  int increment = -1;          // first increment that had no stable path under strain control
  Voigt strain = Voigt::Zero();// strain at the last stable state (the limit point inside that increment)
  double stressBefore = 0.0;   // first principal stress there (MPa)
  double stressAfter = 0.0;    // on the stable branch at the increment's target strain (if jumped)
  bool jumped = false;
  // The trace stalled: the band fully open under a stress target it cannot carry, its opening no
  // longer changing the state (docs/model.md, "Snap-back on the path"); the run then fails.
  bool stalled = false;
};

struct PointRun {
  std::vector<HistoryRow> history;
  SnapBackReport snapBack;
  bool completed = false;
  std::string failure;  // why the run stopped early
};

struct PointSummary {
  double onsetStress = 0.0;     // first principal stress at the onset of cracking (MPa; 0: no onset)
  double peakStress = 0.0;      // max first principal stress (MPa)
  double strainAtPeak = 0.0;    // first principal strain at the peak
  double dissipation = 0.0;     // per unit volume (MPa)
  double effectiveSize = 0.0;   // H
  double energyPerArea = 0.0;   // H x dissipation (N/mm)
  double finalWork = 0.0;
};

using RowObserver = std::function<void(const HistoryRow&, int done, int total)>;

PointRun runPoint(const PointScene& scene, const RowObserver& observe = {});
PointSummary summarise(const PointScene& scene, const PointRun& run);
int totalIncrements(const PointScene& scene);

}  // namespace ecm::driver
