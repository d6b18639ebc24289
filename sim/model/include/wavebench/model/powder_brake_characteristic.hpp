#pragma once
// The magnetic-powder brake's laws, in one place for the gear model's load brake (an ODE
// state, powder_brake.hpp) and the simulated bench's brake (stepped exactly,
// simdevices::PowderBrakePhysics):
// Static curve (rising): T = k·I for threshold ≤ I, k = rated_torque / rated_current; 0 below
// the threshold (the powder chains do not form); T saturates at the rated torque.
// Falling: magnetic remanence keeps the curve higher — a play operator of width w on the
// current: I_eff follows I upwards, and downwards only once I < I_eff − w, so on the falling
// branch T = curve(I + w).
// Lag: dT/dt = (T_ss − T)/τ with T_ss = curve(I_eff), τ_rise when T_ss > T, τ_fall otherwise.
// Holding: up to T at standstill; slipping at T, the slip power T·|ω| heats a lumped mass:
// C·dθ/dt = T·|ω| − G·(θ − θ_ambient).
#include "wavebench/model/powder_brake_params.hpp"

namespace wavebench::model {

class PowderBrakeCharacteristic {
 public:
  explicit PowderBrakeCharacteristic(const PowderBrakeParams& p) : p_(p) {}

  double torque_per_amp() const noexcept { return p_.rated_torque_nm / p_.rated_current_a; }
  // Rising static curve T(I), I the current after the play operator.
  double static_torque(double effective_current) const noexcept;
  // Falling static curve: what the powder keeps once the current came down to `current`.
  double falling_torque(double current) const noexcept {
    return static_torque(current + p_.hysteresis_a);
  }
  // The play operator: the effective current once the coil current moved to `current` from a
  // state whose effective current was `effective`.
  double next_effective_current(double effective, double current) const noexcept;
  // The lag's time constant from `torque` towards `target`.
  double lag_time_constant(double target, double torque) const noexcept {
    return target > torque ? p_.tau_rise_s : p_.tau_fall_s;
  }
  // Current the rising curve needs for torque T (the inverse of static_torque within range).
  double current_for_torque(double torque) const noexcept;
  // Current that brings the static torque to T from a state of effective current `effective`:
  // the rising inverse when T is above the present curve, and below it the falling branch's
  // inverse (I = T/k − w), so a torque-mode controller lands on T from either side.
  double current_for_torque_from(double torque, double effective) const noexcept;
  bool has_thermal_mass() const noexcept { return p_.heat_capacity_j_per_k > 0.0; }
  // dθ/dt of the lumped thermal mass at `temperature` under `slip_power` (needs a mass).
  double temperature_rate(double temperature, double slip_power) const noexcept {
    return (slip_power - p_.heat_loss_w_per_k * (temperature - p_.ambient_c)) /
           p_.heat_capacity_j_per_k;
  }
  const PowderBrakeParams& params() const noexcept { return p_; }

 private:
  PowderBrakeParams p_;
};

}  // namespace wavebench::model
