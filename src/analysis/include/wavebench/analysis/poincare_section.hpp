#pragma once
// Phase portrait and Poincare section of the twist (Delta against Delta'), strobed once per
// period of one excitation term by the term's own angle a*theta1 + b*theta2, so the section
// stays right when the speed varies.

#include <span>
#include <string>
#include <vector>

namespace wavebench::analysis {

struct PhasePoint {
  double x = 0;  // Delta [rad]
  double v = 0;  // Delta' [rad/s]
};

struct PhasePortrait {
  std::vector<PhasePoint> points;
  std::string x_channel = "twist";
  std::string v_channel = "twist_rate";
};

struct PoincareSection {
  std::vector<PhasePoint> points;
  std::vector<double> t;               // strobe times [s]
  std::string excitation_source;       // term whose period strobes
  double excitation_frequency_hz = 0;  // at the mean speed
};

// Strobe (x, v) where `phase` (monotone, rad) crosses multiples of 2 pi; linear interpolation
// between samples. phase may decrease (reverse rotation).
PoincareSection strobe_on_phase(std::span<const double> t, std::span<const double> phase,
                                std::span<const double> x, std::span<const double> v);

}  // namespace wavebench::analysis
