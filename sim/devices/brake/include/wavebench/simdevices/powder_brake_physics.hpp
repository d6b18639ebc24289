#pragma once
// Magnetic-powder brake of the simulated bench (bench.md §3): the laws of
// model::PowderBrakeCharacteristic (static curve, play-operator hysteresis, first-order lag,
// holding at standstill, slip heating), with the coil current as a changing input. step(dt)
// integrates the lag and the heat exactly for inputs held constant over dt, so the simulated
// clock can run at any rate.

#include "wavebench/model/powder_brake_characteristic.hpp"

namespace wavebench::simdevices {

class PowderBrakePhysics {
 public:
  explicit PowderBrakePhysics(model::PowderBrakeParams params = {});

  // Coil current as the controller's current loop sets it (A, ≥ 0).
  void set_coil_current(double amps) noexcept;
  void set_coil_open(bool open) noexcept;
  void set_output_speed(double rad_per_s) noexcept { omega_ = rad_per_s; }
  void set_temperature(double celsius) noexcept { temperature_ = celsius; }

  void step(double dt) noexcept;

  double coil_current() const noexcept { return coil_open_ ? 0.0 : current_; }
  bool coil_open() const noexcept { return coil_open_; }
  double output_speed() const noexcept { return omega_; }
  // Torque the powder transmits at the moment (N·m, ≥ 0): the slip torque, and the most it
  // holds at standstill.
  double torque_capacity() const noexcept { return torque_; }
  // The steady-state torque the lag is heading for.
  double target_torque() const noexcept { return law_.static_torque(effective_current_); }
  // Torque on the output shaft, opposing motion. At standstill it balances `driving_torque`
  // (the torque the gear applies) up to the capacity.
  double shaft_torque(double driving_torque) const noexcept;
  double slip_power() const noexcept;
  double temperature() const noexcept { return temperature_; }
  bool stopped() const noexcept;

  // Rising static curve T(I).
  double static_torque(double current) const noexcept { return law_.static_torque(current); }
  // Current the rising curve needs for torque T (the inverse of static_torque within range).
  double current_for_torque(double torque) const noexcept {
    return law_.current_for_torque(torque);
  }
  // Current that brings the static torque to T from the present magnetic state (see
  // PowderBrakeCharacteristic::current_for_torque_from).
  double current_for_torque_from_here(double torque) const noexcept {
    return law_.current_for_torque_from(torque, effective_current_);
  }
  const model::PowderBrakeParams& params() const noexcept { return law_.params(); }

 private:
  model::PowderBrakeCharacteristic law_;
  double current_ = 0.0;
  double effective_current_ = 0.0;  // current after the hysteresis play operator
  double torque_ = 0.0;
  double omega_ = 0.0;
  double temperature_;
  bool coil_open_ = false;
};

}  // namespace wavebench::simdevices
