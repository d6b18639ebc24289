#pragma once
// The magnetic-powder brake's physical description (bench.md §3, model.md §7): one parameter
// set for the gear model's load brake (powder_brake.hpp) and the simulated bench's brake
// (simdevices::PowderBrakePhysics). Defaults are the simulated bench's brake. SI units, with
// the unit in each name.

namespace wavebench::model {

struct PowderBrakeParams {
  double rated_current_a = 2.0;       // the torque saturates above it
  double rated_torque_nm = 100.0;     // at the rated current: T = k I, k = rated / rated current
  double threshold_current_a = 0.05;  // below it the powder chains do not form: no torque
  double hysteresis_a = 0.04;         // play-operator width on the current (falling curve)
  double tau_rise_s = 0.08;           // current -> torque lag while the torque rises ...
  double tau_fall_s = 0.15;           // ... and while it falls
  // |omega| below this counts as stopped: the brake holds instead of slipping (the gear
  // model's smooth form: the width of tanh(omega / standstill)).
  double standstill_rad_per_s = 1e-3;
  double heat_capacity_j_per_k = 1500.0;  // lumped thermal mass; 0 = no thermal model
  double heat_loss_w_per_k = 3.0;         // to ambient
  double ambient_c = 25.0;
};

// Throws std::invalid_argument naming the field, its value and what was expected.
void check_powder_brake_params(const PowderBrakeParams& p);

}  // namespace wavebench::model
