#pragma once
// ecm-study: speed versus accuracy. A study file names a base scene (an ecm-mpm scene, or an
// ecm-point scene for `kind: point`) and knobs, each a key path of the scene with the values to
// try. Every run is the base scene's YAML with the knob values written in, read back by the
// scene reader (so a knob value is checked exactly like a scene value), and run through the
// ordinary run function into its own folder. Each run's wall time, memory and error against a
// reference (a closed form, or one run of the study taken as the finest setting) go into a
// table, summary.json and a Pareto plot (error against wall time) that marks the settings no
// other run beats on both. Units: mm, N, MPa, tonne, s. Format:
//
//   name: elastic-bar-study
//   kind: mpm                      # mpm (default) | point
//   scene: ../mpm/elastic-bar.yaml # base scene, relative to this file
//   set:                           # optional: written into the base scene for every run
//     end_time: 1.2e-4
//     conditions[0].box: {min: [-10, -10], max: [0, 20]}
//   design: grid                   # grid: every combination | one_at_a_time: the base run plus
//                                  # one knob changed at a time (the others at the base value)
//   knobs:                         # key path -> values (applied in this order)
//     solver.explicitScheme.cfl: [0.1, 0.3, 0.6]
//     particles_per_cell: [1, 2, 3]
//     grid.refinement: [1, 2, 4]   # derived: cells x r (rounded up), cell_size / r
//     time_scale: [0.5, 1, 2]      # derived: every time of the loading x s (see applyTimeScale)
//     scene:                       # derived: the scene file a run starts from (relative to this
//       - ../den/den-4b-coarse.yaml  #   file; the base is `scene:` above), alone or with settings
//       - {file: ../den/den-4b-coarse-implicit.yaml, set: {solver.control.indirect.step: 0.004}}
//                                  #   of its own: explicit and implicit runs in one study, each
//                                  #   with the knobs only its scheme has
//   reference:                     # exactly one of closed_form, run and scene
//     closed_form: bar_vibration   # mpm: fixed-free bar released with a uniform velocity
//     condition: clamp             #   (its reaction is analysed: period and amplitude)
//     # closed_form: uniaxial_tension   point: the enriched point's closed form
//     # run: {particles_per_cell: 3, solver.explicitScheme.cfl: 0.1}   the finest setting (added if not planned)
//     # condition: top             with run: peak_reaction is this condition's largest |R| in history.csv
//     # scene: ../den/den-4b-coarse-implicit.yaml   another scene, run once into reference/ (the
//     #                            implicit solution as the rate-free reference of explicit runs)
//     metrics: [period, amplitude] # optional subset; the run's error is the largest |metric|
//   repeat: 1                      # runs per setting; the shortest wall time is kept
//   samples: 20                    # RVE ensembles: shorthand for the knob bodies[0].rve.seed: [1, 2,
//                                  #   ..., 20] (the last knob; knobs: may then be left out); needs a
//                                  #   reference with a condition, the pulled edge: every sample's
//                                  #   strength is that condition's largest reaction (ensemble.cpp)
//
// Metrics (signed relative errors): bar_vibration: period, amplitude; uniaxial_tension and point
// runs: stress_path (max deviation / f_t'), dissipation, peak_stress; mpm runs: peak_load
// (summary.json), peak_reaction (needs condition), dissipated_energy (with a condition: at
// the smaller of the two runs' last displacements of it; else at the ends), post_peak_curve (needs
// condition: the largest |P - P_ref| over the softening branch as a fraction of the reference's
// peak, postPeakCurveError below).
//
// Key paths: map keys joined by dots, sequence entries by [i] (conditions[0].box.min). A run's
// document is its scene file (the `scene` knob's value, or the base), then the study's `set:`,
// then the scene value's own `set:`, then the plain keys in the order given, then the derived
// knobs.
#include <cmath>
#include <cstddef>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

#include "driver/point_driver.hpp"
#include "io/csv_reader.hpp"
#include "io/yaml_input.hpp"
#include "mpm/scene/scene.hpp"

namespace ecm::study {

enum class StudyKind { Mpm, Point };
enum class StudyDesign { Grid, OneAtATime };
enum class ReferenceKind { BarVibration, UniaxialTension, Run, Scene };

// One knob: a scene key path (or a derived knob) and the values to try, as written.
struct Knob {
  std::string key;
  std::vector<YAML::Node> values;
  int line = 1;  // of the key in the study file
};

struct Setting {  // a key path and its value, with the study file line it came from
  std::string key;
  YAML::Node value;
  int line = 1;
};

// A value of the `scene` knob: the scene file a run starts from and the settings written into it
// before the other knobs. Written as a file name, or as {file: NAME, set: {key path: value}}.
struct SceneChoice {
  std::filesystem::path file;  // resolved against the study file's folder
  std::vector<Setting> set;
  std::string text;            // "STEM" or "STEM key=value ...": the run's value in labels and tables
                               // (two files of one stem are refused as one value given twice)
};
// Reads a value of the `scene` knob (the study file's name and folder, for messages and paths);
// io::InputError when the file does not exist or the value is malformed.
SceneChoice readSceneChoice(const YAML::Node& value, const std::string& studyFile, int line);

// The knob that `samples: N` stands for (the random seed of the scene's first body, an rve: body).
inline constexpr const char* kSampleSeed = "bodies[0].rve.seed";

struct Study {
  std::string name;
  std::string file;  // the study file, for messages
  StudyKind kind = StudyKind::Mpm;
  std::filesystem::path scene;  // base scene
  std::vector<Setting> set;     // written into the base scene for every run
  StudyDesign design = StudyDesign::Grid;
  std::vector<Knob> knobs;
  ReferenceKind reference = ReferenceKind::Run;
  int referenceLine = 1;
  std::string condition;                   // BarVibration: the clamp
  std::vector<Setting> referenceSettings;  // Run: knob values of the reference run
  std::filesystem::path referenceScene;    // Scene: the reference's scene file
  std::vector<std::string> metrics;        // the errors that make up a run's error
  int repeat = 1;
  int samples = 0;  // samples: N (0: not an ensemble); the last knob is then kSampleSeed
};

// The metrics a reference offers, for a study kind.
std::vector<std::string> availableMetrics(StudyKind kind, ReferenceKind reference);

Study readStudy(const io::YamlMap& map);
Study loadStudyFile(const std::filesystem::path& path);

// One run of the plan: its knob values and its validated scene.
struct PlannedRun {
  int id = 0;                       // 1-based, in plan order
  std::string label;                // the knobs away from the base ("base" for none)
  std::vector<std::string> values;  // per knob: the value as text (the base value if not set)
  bool reference = false;
  std::string sceneText;            // the edited scene (YAML), kept in the run folder
  std::filesystem::path sceneFile;  // the file sceneText is read as (its folder resolves material files)
  std::optional<mpm::Scene> scene;       // kind mpm
  std::optional<driver::PointScene> point;  // kind point
  std::size_t particles = 0;        // mpm: seeded particles
  double estimatedSteps = 0.0;      // mpm: end time / time step; point: increments
};

// Every run of the study, each scene read and checked (and, for mpm, seeded): an invalid knob
// value is an InputError "STUDY:LINE: run N (knob=value): SCENE:LINE: reason" before anything
// runs. Runs with identical values are planned once.
std::vector<PlannedRun> planStudy(const Study& study);
// A run's folder, relative to the study folder: runs/NNN-label.
std::string runDirectory(const PlannedRun& run);

// The edits of the study, exposed for tests. Both throw std::invalid_argument.
void setKeyPath(YAML::Node& root, const std::string& path, const YAML::Node& value);
std::optional<YAML::Node> findKeyPath(const YAML::Node& root, const std::string& path);
void applyGridRefinement(YAML::Node& scene, double factor);
// Loading time x s: end_time, output_interval, every history time of conditions and loads;
// velocity histories (velocity, velocity_field scale) divided by s, so that prescribed
// displacements, forces and their paths stay the same. Initial velocities and gravity stay.
void applyTimeScale(YAML::Node& scene, double s);

struct StudyOptions {
  std::filesystem::path outputDir;
  int threads = 2;         // mpm runs
  bool isolate = true;     // mpm runs in a child process (its own peak RSS; a crash stays there)
  bool progress = true;    // a line per run on stderr
  bool resume = false;     // mpm: reuse a run folder whose scene.yaml is this run's (an interrupted study goes on)
  std::ostream* table = nullptr;  // the final table (stdout in ecm-study)
  // mpm: run nothing, only read the run folders (and DIR/reference) that something else filled
  // (the Dask path, python/ecm/study.py) as --resume reads them; a run without its outputs there
  // is failed ("not run"). Point runs still run here (they take milliseconds).
  bool collectOnly = false;
};

struct RunRecord {
  int id = 0;
  std::string label;
  std::vector<std::string> values;
  bool reference = false;
  std::string directory;            // relative to the study folder
  std::string status = "not run";   // completed | failed
  std::string message;              // why a run failed
  double wallTime = NAN;            // s, the shortest of the repeats
  double steps = NAN;               // mpm: time steps; point: increments
  double particles = NAN;
  double updatesPerSecond = NAN;    // particle-updates (point: increments) per second
  double bytesPerParticle = NAN;    // mpm: the solver's particle arrays, cracked points' bands included
  double peakRssMb = NAN;           // mpm isolated: peak resident memory of the run's process
  double cpuTime = NAN;             // mpm isolated: user + system time of the run's process (s)
  double substepped = NAN;          // material updates (point: increments) that were sub-stepped
  std::vector<double> metrics;      // signed relative errors (stress path: / f_t'), per study.metrics
  double error = NAN;               // max |metrics|
  bool pareto = false;
  bool reused = false;              // --resume: the outputs of an earlier study were read
};

struct StudyResult {
  std::vector<RunRecord> runs;
  nlohmann::json reference;  // the closed-form values or the reference run's values
  bool allCompleted = true;
  double studyRssMb = NAN;   // the study's own resident memory (isolated runs start from it)
  nlohmann::json ensemble;   // samples: N: summary.json's "ensemble" (null otherwise)
};

// Runs the plan (the reference run first), writes DIR/study.csv, DIR/summary.json,
// DIR/pareto.png and DIR/runs/NNN-label/, and prints the table to options.table.
StudyResult runStudy(const Study& study, const std::vector<PlannedRun>& plan, const StudyOptions& options);

// Non-dominated points of (cost, error): no other point has cost <= and error <= with one of
// them strictly smaller. Points with a non-finite cost or error are never on the front.
std::vector<bool> paretoFront(const std::vector<double>& cost, const std::vector<double>& error);

// --- RVE ensembles (samples: N, ensemble.cpp) ---

// The sample statistics of n >= 2 values: mean, standard deviation (n - 1), coefficient of
// variation, the two-sided confidence interval of the mean (Student's t) and of the coefficient
// of variation (McKay's approximation as modified by Vangel, 1996), and the samples n_1% the mean
// needs to lie within 1 % at that confidence, n = (t cv / 0.01)^2 iterated on t's degrees.
struct SampleStatistics {
  std::size_t count = 0;
  double mean = NAN, stdDev = NAN, cov = NAN;
  double confidence = 0.95;
  double meanLow = NAN, meanHigh = NAN, covLow = NAN, covHigh = NAN;
  long samplesForOnePercent = 0;
};
SampleStatistics sampleStatistics(const std::vector<double>& x, double confidence = 0.95);

// A two-parameter Weibull fit of positive values, P(x) = 1 - exp(-(x / scale)^modulus): the
// maximum-likelihood modulus and scale, and the fit's quality on the Weibull plot (ln x against
// ln(-ln(1 - F)), median ranks F = (i - 0.3) / (n + 0.4)): the coefficient of determination R^2
// of the points against the fitted line, and the Kolmogorov-Smirnov distance of the fit. The
// intervals at `confidence` are the maximum-likelihood estimates' asymptotic ones (the inverse
// Fisher information: var(m) = 0.6079 m^2 / n, var(scale) = 1.1087 scale^2 / (n m^2)), taken on
// ln m and ln scale so that they stay positive; with few samples the modulus is biased high
// and its interval too narrow (docs/dask.md, "Ensembles").
struct WeibullFit {
  double modulus = NAN, scale = NAN;
  double rSquared = NAN, ksDistance = NAN;
  double confidence = 0.95;
  double modulusLow = NAN, modulusHigh = NAN, scaleLow = NAN, scaleHigh = NAN;
};
WeibullFit fitWeibull(const std::vector<double>& x, double confidence = 0.95);

// An ensemble's statistics as the terminal shows them (summary.json's "ensemble"): per mesh the
// samples, the mean strength with its interval, the coefficient of variation with its interval,
// and the Weibull modulus and scale with theirs. Empty for a null ensemble.
std::string ensembleTable(const nlohmann::json& ensemble);

// The runs that did not complete, one line each with their status and message, after a line
// that counts them; "" when every run completed. The tool prints it last, before it exits 1.
std::string notCompletedList(const StudyResult& result);

// --- closed forms and measures (exposed for tests) ---

// Fixed-free bar released with v0: the clamp reaction is a square wave of period 4 L / c and
// amplitude rho c v0 A (d'Alembert; e.g. Graff, Wave Motion in Elastic Solids, sec. 1.2). Read
// from the scene's first rectangle body (along x) and its material (nu = 0); throws
// std::invalid_argument if the scene is not such a bar.
struct BarVibration {
  double period = 0.0;     // s
  double amplitude = 0.0;  // N
};
BarVibration barVibrationClosedForm(const mpm::Scene& scene);

// Period and amplitude of a square-wave-like reaction history: sign changes found with a
// Schmitt trigger at +-amplitude/2 (ringing near zero is not counted), period = twice the mean
// spacing of the zero crossings (the first crossing is at T/2 when only one is found), amplitude
// = mean |R| over the middle half of every half period.
struct SquareWave {
  double period = NAN;
  double amplitude = NAN;
  int crossings = 0;
};
SquareWave measureSquareWave(const std::vector<double>& time, const std::vector<double>& reaction, double amplitude);

// The enriched point in uniaxial tension (plane stress), material/uniaxial_closed_form.hpp, up
// to the macro strain `strainEnd`: the curve (elastic branch, then the band branch), its peak
// and the dissipation per volume. Throws std::invalid_argument when the macro curve turns back
// (H beyond the snap-back size).
struct UniaxialReference {
  std::vector<double> strain, stress;
  double peakStress = 0.0;
  double dissipation = 0.0;  // per unit volume of the point (MPa), f int F dD
};
UniaxialReference uniaxialTensionClosedForm(const MaterialParams& material, double effectiveSize, double strainEnd);

// The load-displacement curve of a condition from history.csv: its displacement and reaction
// along its driven component, the one whose displacement reaches the largest magnitude.
struct LoadCurve {
  std::vector<double> displacement, load;  // mm, N
  std::vector<double> dissipated;          // N mm (dissipated_Nmm), per row
};
LoadCurve loadCurve(const io::CsvTable& history, const std::string& condition);
// The dissipated energy of two curves at the smaller of their last displacements (each
// interpolated linearly; displacements increasing): {run, reference}, NAN when a curve has none.
std::pair<double, double> dissipatedAtEqualDisplacement(const LoadCurve& run, const LoadCurve& reference);

// The post-peak curve error: the largest |P - P_ref| over the softening branch, the
// displacements past both peaks up to the smaller of the two last displacements (at the sample
// points of both curves, each interpolated linearly in the other), divided by the reference's
// peak load. NAN when the branches do not overlap. Displacements must increase along the rows.
double postPeakCurveError(const LoadCurve& run, const LoadCurve& reference);

// max |y(x_i) - curve(x_i)| over the sample points x_i inside the curve's range, the curve
// interpolated linearly (x increasing).
double maxDeviation(const std::vector<double>& x, const std::vector<double>& y, const std::vector<double>& curveX,
                    const std::vector<double>& curveY);

}  // namespace ecm::study
