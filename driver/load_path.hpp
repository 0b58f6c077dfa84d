#pragma once
// A point's load path: segments of increments, each component (eps_xx | sig_xx, eps_yy | sig_yy,
// gamma_xy | sig_xy) strain- or stress-controlled, with its target at the end of the segment.
// An opening-controlled segment is driven by the band's normal jump instead of a strain.
#include <array>
#include <string>
#include <vector>

#include "material/voigt.hpp"

namespace ecm::driver {

enum class Control { Strain, Stress };

struct Segment {
  std::array<Control, 3> control{Control::Strain, Control::Strain, Control::Strain};
  Voigt target = Voigt::Zero();  // strain (engineering shear) or stress (MPa) at the segment end
  int increments = 1;
  // Opening control: the normal jump [u].n (mm) goes to `openingTarget`; the strain-controlled
  // components then only give the direction of the strain path (their targets are ratios).
  bool openingControl = false;
  double openingTarget = 0.0;
  double firstOpeningIncrement = 0.0;  // > 0: geometric spacing starting with this increment (mm)
  bool hasStressControl() const {
    return control[0] == Control::Stress || control[1] == Control::Stress || control[2] == Control::Stress;
  }
};

// The usual paths, built from a few numbers (strains are totals, e.g. strain = 2e-4).
struct PresetPath {
  std::string name;           // see presetNames()
  double strain = 0.0;        // main strain magnitude
  int increments = 100;       // per segment
  double ratio = 1.0;         // biaxial: eps_yy / eps_xx
  double shear = 0.0;         // tension_then_shear: gamma_xy at the end
  double angle = 1.5707963267948966;  // rotating_principal_axes: total rotation (rad)
  std::vector<double> cycleStrains;   // cyclic: peak strains of successive cycles
  double opening = 0.0;       // > 0: after onset, continue under opening control to this jump (mm)
  double firstOpeningIncrement = 0.0;  // > 0: geometric opening increments starting with this (mm)
};

const std::vector<std::string>& presetNames();
// Normal jump at increment k of an opening segment (uniform, or geometric from its first increment).
double openingAt(const Segment& s, double start, int k);
std::vector<Segment> presetSegments(const PresetPath& preset, double poissonRatio);

}  // namespace ecm::driver
