#pragma once
// Mesoscale samples of cement-matrix composites for RVE scenes: non-overlapping circular
// inclusions in a square matrix, each wrapped by an interfacial transition zone (ITZ) ring.
// Units: mm.
//
// Grading: a curve of (diameter, cumulative passing fraction) points, increasing in both; the
// passing fraction is read as the fraction of the inclusion AREA (of the 2D section) made of
// inclusions smaller than d, normalised between the first and the last point. fullerGrading()
// builds the usual Fuller curve P(d) = (d / d_max)^q (q = 0.5) between d_min and d_max.
//
// Generation (random sequential addition, largest first):
//  1. The target inclusion area f L^2 (inclusions only, without their ITZ) is split over the
//     grading classes [d_i, d_i+1] in proportion to P(d_i+1) - P(d_i).
//  2. From the coarsest class down, diameters are drawn uniformly in the class, each capped so
//     that the circle does not exceed the area still to place (the remainder of a class carries
//     over to the next finer non-empty one); so the area placed never exceeds the target and,
//     unless the packing jams, falls short of it by less than one smallest inclusion
//     (pi d_min^2 / 4). The drawn diameters of a class are placed largest first.
//  3. Each inclusion is placed at a uniformly random centre where its outer ITZ circle (radius
//     r + t) keeps at least `gap` from every other outer ITZ circle and from the four sides of
//     the square: |c1 - c2| >= r1 + r2 + 2 t + gap, and r + t + gap <= c <= L - r - t - gap.
//     No inclusion is cut by the boundary, so the loaded edges are matrix only.
//  4. An inclusion that finds no place in `attempts` tries is dropped; after three misses in a
//     row the class stops the round. The area not placed is drawn again in further rounds (at
//     most 8, with the class narrowed below the smallest miss, again largest first) until a
//     round places nothing; then it carries over to the finer classes. If the area placed in the
//     end is below (target - tolerance), the target is infeasible: RveInfeasible names the
//     target and what was reached.
//
// Random numbers: std::mt19937_64 (its output sequence is fixed by the standard) turned into
// uniform doubles by u = (x >> 11) 2^-53 in [0, 1): the same seed gives the same sample on
// every standard library (std distributions would not).
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "material/voigt.hpp"
#include "mpm/scene/geometry.hpp"

namespace ecm::mpm {

struct GradingPoint {
  double diameter = 0.0;  // mm
  double passing = 0.0;   // cumulative passing fraction (by area), any scale: normalised
};

// Fuller-type curve P(d) = (d / dMax)^exponent sampled at `classes` + 1 diameters spaced
// geometrically between dMin and dMax.
std::vector<GradingPoint> fullerGrading(double dMin, double dMax, double exponent = 0.5, int classes = 8);

struct RveParams {
  double side = 25.0;                // L (mm): the square [origin, origin + L]^2
  Vec2 origin = Vec2::Zero();        // mm
  std::uint64_t seed = 1;
  double volumeFraction = 0.4;       // target inclusion area fraction (ITZ not counted), (0, 1)
  std::vector<GradingPoint> grading = fullerGrading(1.0, 4.0);
  double itzThickness = 0.1;         // t (mm), > 0
  double gap = -1.0;                 // mm, >= 0; negative: the default 0.1 d_min
  int attempts = 20000;              // random trial centres per inclusion before it is dropped
  double tolerance = 0.005;          // accepted shortfall of the achieved fraction (absolute)

  double minDiameter() const { return grading.empty() ? 0.0 : grading.front().diameter; }
  double maxDiameter() const { return grading.empty() ? 0.0 : grading.back().diameter; }
  double effectiveGap() const { return gap >= 0.0 ? gap : 0.1 * minDiameter(); }
  // Throws std::invalid_argument naming the bad value (also when the sample could need more
  // than 10^6 inclusions: f L^2 / (pi d_min^2 / 4)).
  void validate() const;
};

struct Inclusion {
  Vec2 center = Vec2::Zero();  // mm
  double radius = 0.0;         // mm, of the inclusion (the ITZ ring reaches radius + t)
};

struct RveStats {
  double targetFraction = 0.0;
  double achievedFraction = 0.0;  // inclusion area / L^2
  double itzFraction = 0.0;       // ITZ ring area / L^2
  double matrixFraction = 0.0;    // the rest
  std::size_t count = 0;
  double minDiameter = 0.0, meanDiameter = 0.0, maxDiameter = 0.0;  // mm, of the placed inclusions
  std::size_t dropped = 0;        // inclusions that found no place (their area went to finer classes)
};

struct RveSample {
  RveParams params;
  std::vector<Inclusion> inclusions;  // largest first (placement order)
  RveStats stats;
};

// The target fraction could not be reached within the attempts.
struct RveInfeasible : std::runtime_error {
  RveInfeasible(double target, double reached, std::size_t placed);
  double target, reached;
};

// Throws std::invalid_argument for bad parameters, RveInfeasible when the target is not reached.
RveSample generateRve(const RveParams& params);

// The three phases as scene bodies, in override order: the matrix square, then every ITZ circle
// (radius r + t), then every inclusion circle (radius r). Arguments are material indices.
std::vector<Body> rveBodies(const RveSample& sample, int matrix, int inclusion, int itz);

}  // namespace ecm::mpm
