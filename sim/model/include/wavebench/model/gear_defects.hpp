#pragma once
// The TE excitation of a simulated unit's defects (gear_params.hpp, GearDefects), added to e by
// the simulated bench's plant. Header-only: the plant uses the model's types without linking it.
//
// A tooth pulse is a raised cosine of the mesh phase psi (the angle of a wave lobe past the
// damaged tooth, times U, wrapped to (-pi, pi]): A (1 + cos(psi / w)) / 2 for |psi| < pi w,
// 0 elsewhere, so it is smooth (C1) and periodic in the angle the tooth meshes in:
//   Flexspline tooth j (turns with the output):  psi = U (theta1 + theta2 - 2 pi j / z_F)
//   Circular Spline tooth j (fixed):             psi = U (theta1 - 2 pi j / z_C)
// With theta1 = N theta2 per output revolution the first repeats U (N + 1) times (output
// orders k U (N + 1), the (U, U) family's and its harmonics), the second U N times (output
// orders k U N, the (U, 0) family's).

#include <cmath>
#include <numbers>

#include "wavebench/model/gear_params.hpp"

namespace wavebench::model {

struct DefectExcitation {
  double value = 0;  // added to e [rad]
  double rate = 0;   // added to e' [rad/s]
};

// Mesh phase of a tooth defect and its rate.
inline DefectExcitation tooth_mesh_phase(const ToothDefect& d, const GearGeometry& g, double theta1,
                                         double theta2, double omega1, double omega2) noexcept {
  const double u = g.wave_number;
  const bool flex = d.part == DefectPart::kFlexspline;
  const int z = flex ? g.z_flex : g.z_circ;
  const double tooth_angle = z > 0 ? 2 * std::numbers::pi * d.tooth / z : 0.0;
  const double angle = flex ? theta1 + theta2 : theta1;
  double psi = u * (angle - tooth_angle);
  psi -= 2 * std::numbers::pi * std::round(psi / (2 * std::numbers::pi));
  return {psi, u * (flex ? omega1 + omega2 : omega1)};
}

// travel_rev: output revolutions the unit has turned (either direction) since it started.
inline DefectExcitation defect_excitation(const GearDefects& defects, const GearGeometry& g,
                                          double theta1, double theta2, double omega1,
                                          double omega2, double travel_rev) noexcept {
  DefectExcitation out;
  for (const auto& d : defects.teeth) {
    if (travel_rev < d.onset_rev || !(d.width > 0)) continue;
    const auto [psi, psi_rate] = tooth_mesh_phase(d, g, theta1, theta2, omega1, omega2);
    if (std::abs(psi) >= std::numbers::pi * d.width) continue;
    out.value += 0.5 * d.amplitude_rad * (1 + std::cos(psi / d.width));
    out.rate += -0.5 * d.amplitude_rad / d.width * std::sin(psi / d.width) * psi_rate;
  }
  for (const auto& r : defects.rising_once_per_rev) {
    const double turned = travel_rev - r.onset_rev;
    if (turned <= 0) continue;
    const double amplitude = r.growth_rad_per_rev * turned;
    const double arg = theta2 + r.phase_rad;
    out.value += amplitude * std::sin(arg);
    out.rate += amplitude * omega2 * std::cos(arg) +
                r.growth_rad_per_rev * std::abs(omega2) / (2 * std::numbers::pi) * std::sin(arg);
  }
  return out;
}

}  // namespace wavebench::model
