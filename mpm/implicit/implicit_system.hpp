#pragma once
// The discrete quasi-static equilibrium of one implicit load step (docs/implicit.md): the grid
// is a finite-element mesh for the step, the particles its integration points. With the nodal
// displacement increments du (two per node, x and y), a particle's strain increment is
// d eps_p = B_p du (small strain, engineering shear), its stress and consistent tangent D_p come
// from Material::update on a copy of its committed state, and
//   internal force  f_int = sum_p V_p B_p^T sigma_p
//   tangent         K     = sum_p V_p B_p^T D_p B_p   (over the unknown components only)
// The stencils are those of the step's start (the particles move when the step is committed).
// Sums go particle by particle in index order: the same bits on any number of threads.
#include <Eigen/Sparse>

#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

#include "mpm/setup/crack_paths.hpp"
#include "mpm/core/shape_function.hpp"
#include "mpm/setup/step_setup.hpp"

namespace ecm::mpm {

// The components of the nodes some particle's stencil reaches, numbered: a node component is an
// unknown (>= 0), prescribed (kPrescribed) or outside the body (kInactive).
struct DofMap {
  static constexpr std::int32_t kInactive = -1, kPrescribed = -2;
  std::vector<std::int32_t> unknownOf;  // per node component 2 n + d
  std::vector<std::int32_t> component;  // per unknown: its node component 2 n + d
  int unknowns() const { return static_cast<int>(component.size()); }
};

// The step's fixed geometry: the particles' stencils at its start, the unknowns, and the sparse
// pattern of K with, per particle, where each entry of its element matrix goes in K's values.
// And K's elastic part: the sum over the points undamaged at the step's start with their elastic
// stiffness, assembled once per step (a trial adds what its cracked points change).
struct StepGeometry {
  std::vector<Stencil> stencils;            // per particle
  std::vector<std::uint8_t> prescribed;     // per node component, as given
  std::vector<std::uint8_t> reached;        // per node component: some stencil gives it a weight or gradient (not exactly 0)
  std::vector<double> share;                // per node: sum_p S_np V_p over a cell's volume (mpm/implicit/node_ties.hpp)
  DofMap dofs;
  Eigen::SparseMatrix<double> pattern;      // K's pattern (column major, compressed), values 0
  int stencilNodes = 4;                     // S x S nodes per stencil
  std::vector<std::int32_t> entryOf;        // per particle, (2 S^2)^2 positions in pattern's values (-1: not an unknown pair)
  std::vector<std::uint8_t> undamaged;      // per particle: no band, no smeared damage at the step's start
  Eigen::VectorXd elasticValues;            // per entry of `pattern`: sum over undamaged points of V B^T D_e B
  long patternBuilds = 0;                   // how often the pattern was built (it is kept while no stencil moves to other nodes)
  // Where enriched points may open bands in the step (docs/model.md, "Crack paths"): frozen while
  // the step iterates, grown between its tries. nullptr: everywhere (CrackPathRule::Free).
  const CrackPaths* crackPaths = nullptr;
};

// Locates every particle's stencil (false if one left the grid: `outside` names it) and
// numbers the unknowns: components of reached nodes, minus those `prescribed` (2 n + d -> true).
// A geometry of an earlier step whose stencils all start at the same nodes, with the same
// prescribed components, keeps its unknowns and pattern; the weights and K's elastic part are
// always recomputed.
bool stepGeometry(const StepSetup& setup, const Particles& particles, const std::vector<std::uint8_t>& prescribed,
                  StepGeometry& geometry, std::size_t& outside);
// Per grid node, 1 where some particle's shape function at its present position has a weight or
// a gradient that is not exactly zero: the nodes that carry the body.
std::vector<std::uint8_t> reachedNodes(const StepSetup& setup, const Particles& particles);
// A geometry from its stencils' first nodes and its prescribed components (a restart): the
// unknowns and the pattern, weights zero and no elastic part; the next stepGeometry compares
// with it. False when a stencil would reach outside the grid.
bool restoreGeometry(const StepSetup& setup, std::size_t particles, const std::vector<std::uint8_t>& prescribed,
                     const std::vector<std::int32_t>& bases, StepGeometry& geometry);

// A point's state just after a snap-back release in an iterate of an attempt (docs/implicit.md,
// "Releases kept within a step"): the attempt's later trials update the point from there, with
// the rest of their strain increment, instead of from its committed state.
struct ReleasedStart {
  Voigt increment = Voigt::Zero();        // the strain increment, from the committed state, that released it
  Voigt strain = Voigt::Zero();           // its strain there
  std::optional<BandState> band, secondBand;
  double dissipation = 0.0;               // per unit volume (MPa), booked by the step up to there
};
// The released points of an attempt: per particle the index of its start in `starts`, or -1.
struct ReleasedStarts {
  std::vector<std::int32_t> of;
  std::vector<ReleasedStart> starts;
};

// The dashpots of a stabilised step (docs/implicit.md, "Stabilised steps"): alpha, and the
// increments (per node component) from which they stretch (nullptr: the step's start).
struct Dashpots {
  double alpha = 0.0;
  const Eigen::VectorXd* from = nullptr;
};

// The particles' states at the end of the step for a trial du, not committed.
struct Trial {
  std::vector<Voigt> strain, stress;              // per particle
  std::vector<double> integrity;                  // smeared crack (empty otherwise)
  std::vector<std::optional<BandState>> band, secondBand;  // per particle: its bands after the step
  std::vector<double> dissipation;                // per particle, per unit volume (MPa)
  // A stabilised step (docs/implicit.md, "Stabilised steps"): per particle the dashpot's stress
  // alpha D_e d eps at its cracked points, which the internal forces carry and the committed
  // state does not; empty when the step is not stabilised.
  std::vector<Voigt> dashpot;
  std::vector<Tangent> tangents;                  // per particle: its consistent tangent D_p
  std::vector<std::uint8_t> elastic;              // per particle: D_p is its material's elastic stiffness
  Eigen::VectorXd internalForce;                  // per node component (N)
  Eigen::SparseMatrix<double> tangent;            // over the unknowns (when asked)
  Eigen::VectorXd tangentTimesDirection;          // sum_p V B^T D B direction, per node component (when asked)
  long released = 0;                              // snap-backs released (UpdateOptions::snapBack)
  std::vector<std::pair<std::size_t, ReleasedStart>> releases;  // with `kept` given: each released point's start
  double onsetOvershoot = 0.0;                    // the most a point that cracks in the trial passed its onset by: sqrt(Y_e / Y_onset) - 1
  std::vector<OnsetCandidate> held;               // tracked crack paths: points past onset off every path, kept intact (particle order)
  std::size_t failed = SIZE_MAX;                  // first particle whose update failed
  UpdateResult failure;                           // its result
};

// The trial of du (per node component), with K assembled when `withTangent`. Each point's update
// starts from its committed state; a failed update leaves `failed` set and the rest undefined.
// With `direction` (per node component), also the tangent's product with it over all
// components: the predictor's load from the prescribed increments.
// With `secant` (per particle), the flagged one-band enriched points carry their secant tangent
// (TwoPhasePoint::secantTangent) instead of the consistent one.
// With `kept`, the points it holds start from their released states, and the trial lists the
// points it releases with their starts (Trial::releases).
// With `dashpots` (alpha > 0), each point cracked in the trial carries a dashpot in parallel,
// alpha D_e (d eps - d eps of `from`) (Trial::dashpot), and its tangent alpha D_e more
// (docs/implicit.md, "Stabilised steps").
void evaluateTrial(const StepSetup& setup, const Particles& particles, const StepGeometry& geometry,
                   const Eigen::VectorXd& du, bool withTangent, SnapBackPolicy snapBack, Trial& trial,
                   const Eigen::VectorXd* direction = nullptr, const std::vector<std::uint8_t>* secant = nullptr,
                   const ReleasedStarts* kept = nullptr, const Dashpots& dashpots = {});
// Keeps the releases of `trial` in `kept` (a point released again gets its new start).
void keepReleases(const Trial& trial, std::size_t particles, ReleasedStarts& kept);
// K of a trial evaluated without it: the elastic part plus, in particle order, what the
// points that are not elastic in the trial change.
void assembleTangent(const StepSetup& setup, const Particles& particles, const StepGeometry& geometry, Trial& trial);

}  // namespace ecm::mpm
