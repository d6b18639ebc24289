#pragma once
// Magnetic-powder brake load of the gear model (model.md §7): the laws of
// powder_brake_characteristic.hpp in the model's state form. The torque capacity tau is an ODE
// state lagging towards the static curve at the constant coil current (through the play
// operator from a coil switched on at t = 0); the brake opposes output speed with
// tau * tanh(omega / standstill), which holds the shaft up to tau when it stops. The slip power
// heats a lumped thermal mass (a second state) when the brake has one.
#include "wavebench/model/powder_brake_characteristic.hpp"

namespace wavebench::model {

class PowderBrake {
 public:
  // Throws std::invalid_argument naming a parameter out of range.
  PowderBrake(const PowderBrakeParams& p, double coil_current_a);
  const PowderBrakeCharacteristic& characteristic() const noexcept { return law_; }
  double target_capacity() const noexcept { return target_; }
  double capacity_rate(double capacity) const noexcept;
  double torque(double capacity, double omega) const noexcept;
  bool has_thermal_state() const noexcept { return law_.has_thermal_mass(); }
  double temperature_rate(double temperature, double slip_power) const noexcept {
    return law_.temperature_rate(temperature, slip_power);
  }
  const PowderBrakeParams& params() const noexcept { return law_.params(); }

 private:
  PowderBrakeCharacteristic law_;
  double target_;  // the static torque at the coil current
};

}  // namespace wavebench::model
