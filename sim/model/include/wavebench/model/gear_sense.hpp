#pragma once
// The one place where the bench's angles become transmission error (bench.md §4, model.md §1):
// TE = θ2 − θ1/N with θ2 = s·θ_out, s the output direction sign of the gear on this bench.

#include <cmath>
#include <numbers>

#include "wavebench/model/angle_units.hpp"

namespace wavebench::model {

struct GearSense {
  double ratio = 0;        // N > 0
  int direction_sign = 1;  // s: +1 or -1

  // Throws std::invalid_argument naming the key and value when N <= 0 or s is not ±1.
  void validate() const;
  // Output angle in the model's convention (θ2).
  double model_output_angle(double theta_out_rad) const { return direction_sign * theta_out_rad; }
  // TE at the output, rad. Angles unwrapped, θ_in and θ_out from the same SYNC. The encoders'
  // zeros are arbitrary by whole turns (a multi-turn output encoder's turn count, the input
  // counted from power-up), which shifts θ2 − θ1/N by multiples of 2π/N: TE is taken in
  // (−π/N, π/N], where a gear's TE of a few arcmin lies (π/N is 108 arcmin at N = 100).
  double transmission_error(double theta_in_rad, double theta_out_rad) const {
    const double te = direction_sign * theta_out_rad - theta_in_rad / ratio;
    const double turn = 2 * std::numbers::pi / ratio;
    return te - turn * std::round(te / turn);
  }
};

}  // namespace wavebench::model
