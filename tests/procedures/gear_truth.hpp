#pragma once
// What the simulated unit must show, computed from its own true parameters and nothing of the
// procedures: TE excitation at the settled angles, elastic twist under the held torque through
// the three-segment law, and the backlash flank the approach leaves the mesh on.

#include <algorithm>
#include <cmath>
#include <numbers>
#include <variant>
#include <vector>

#include "wavebench/model/gear_params.hpp"

namespace wavebench::procedures::testing {

inline constexpr double kArcminPerRadTruth = 180.0 * 60.0 / std::numbers::pi;

inline double true_excitation(const model::GearParams& g, double theta1, double theta2) {
  double e = 0;
  for (const auto& t : g.te_terms) {
    e += t.amplitude_rad * std::sin(t.order_input * theta1 + t.order_output * theta2 + t.phase_rad);
  }
  return e;
}

// Elastic twist [rad] under torque T [N·m, signed] of the unit's three-segment law.
inline double true_twist(const model::GearParams& g, double torque) {
  const auto& s = std::get<model::ThreeSegmentStiffness>(g.stiffness.law);
  const double t = std::abs(torque);
  double x = 0;
  if (t <= s.t1) {
    x = t / s.k1;
  } else if (t <= s.t2) {
    x = s.t1 / s.k1 + (t - s.t1) / s.k2;
  } else {
    x = s.t1 / s.k1 + (s.t2 - s.t1) / s.k2 + (t - s.t2) / s.k3;
  }
  return std::copysign(x, torque);
}

// TE = θ2 − θ1/N at rest after an approach in `travel` (+1 forward, −1 reverse) with the gear
// holding `torque` (signed, the direction it transmits): Δ = θ1/N − θ2 − e sits on the flank.
inline double true_static_te(const model::GearParams& g, double theta1, double theta2,
                             double torque, int travel) {
  const double twist = travel * g.backlash.total_rad / 2 + true_twist(g, torque);
  return -twist - true_excitation(g, theta1, theta2);
}

// Mean, peak-to-peak and population standard deviation of the truth at the positions,
// computed here independently of the procedure's statistics.
struct Stats {
  double mean = 0, p2p = 0, std = 0;
};

inline Stats stats(const std::vector<double>& v) {
  Stats s;
  for (double x : v) s.mean += x;
  s.mean /= static_cast<double>(v.size());
  for (double x : v) s.std += (x - s.mean) * (x - s.mean);
  s.std = std::sqrt(s.std / static_cast<double>(v.size()));
  const auto [lo, hi] = std::minmax_element(v.begin(), v.end());
  s.p2p = *hi - *lo;
  return s;
}

}  // namespace wavebench::procedures::testing
