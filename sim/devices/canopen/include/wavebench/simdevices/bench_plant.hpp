#pragma once
// The mechanics behind the simulated bench: motor rotor + wave generator (J1), the gear's
// elastic twist with backlash and transmission error, and the output side (J2) with the brake.
// A fixed-step, semi-implicit time stepper in the model's equations (model.md §2): it only
// needs to be stable and causal at the servo's control rate, not adaptive, so that the
// devices can run it in real time or by SYNC ticks. Swap in GearModel behind the same
// interface when the full model is wanted.

#include <cstdint>
#include <functional>

#include "wavebench/model/gear_params.hpp"

namespace wavebench::simdevices {

struct PlantState {
  double t = 0;
  double theta_in = 0;           // theta1 [rad]
  double omega_in = 0;           // [rad/s]
  double theta_out = 0;          // theta2 [rad] in the model's convention
  double omega_out = 0;          // [rad/s]
  double twist = 0;              // Delta = theta1/N - theta2 - e [rad]
  double te = 0;                 // theta2 - theta1/N [rad]
  double gear_torque = 0;        // T_g at the output [N*m]
  double motor_torque = 0;       // T_m [N*m]
  double brake_torque = 0;       // torque the brake exerts on the output [N*m] (opposes motion)
  double shaft_torque = 0;       // torque through the sensor into brake and load [N*m]
  double output_travel_rad = 0;  // output angle turned either way since start (defect onsets)
};

class SimulatedBenchPlant {
 public:
  // Throws std::invalid_argument naming the parameter when `params` cannot be simulated.
  explicit SimulatedBenchPlant(model::GearParams params, double max_substep = 2e-5);
  SimulatedBenchPlant(const SimulatedBenchPlant&) = delete;
  SimulatedBenchPlant& operator=(const SimulatedBenchPlant&) = delete;

  // Held constant over the next step() calls.
  void set_motor_torque(double torque_nm) noexcept { motor_torque_ = torque_nm; }
  // The brake's available torque [N*m, >= 0]: it holds the output up to it and slips above.
  void set_brake_torque(double torque_nm) noexcept { brake_limit_ = torque_nm < 0 ? 0 : torque_nm; }
  double brake_torque_setting() const noexcept { return brake_limit_; }

  void step(double dt);
  const PlantState& state() const noexcept { return state_; }
  const model::GearParams& params() const noexcept { return params_; }
  double ratio() const noexcept { return ratio_; }

  // The gear's laws, exposed for tests against closed forms.
  double te_excitation(double theta_in, double theta_out) const;
  double stiffness_torque(double x, double theta_in, double theta_out) const;  // K-term at x
  double backlash_filter(double twist) const;                                  // g(Delta)

 private:
  void substep(double h);
  double te_rate(double theta_in, double theta_out, double omega_in, double omega_out) const;
  double friction_torque(double omega_in) const;

  model::GearParams params_;
  double ratio_;
  double damping_;
  double max_substep_;
  double motor_torque_ = 0;
  double brake_limit_ = 0;
  PlantState state_;
};

// A gear the simulated bench can use out of the box, with the character of seed 004's unit
// (N = 100 from 200/202 teeth, catalogue three-segment stiffness, 0.3 arcmin backlash, TE
// harmonics of a few arcmin and a constant offset). These are the bench's "true" parameters,
// deliberately not the twin's nominal ones.
model::GearParams default_bench_gear();

}  // namespace wavebench::simdevices
