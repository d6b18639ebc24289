#pragma once
// Magnetic-powder brake load (model.md §7, bench.md). The torque capacity tau follows the coil
// current through a first-order lag towards a band between the rising and the falling static
// curves (hysteresis: inside the band it stays put). The brake opposes output speed with
// tau * tanh(omega / holding_speed), which holds the shaft up to tau when it stops. The slip
// power heats a lumped thermal mass.
#include "wavebench/model/gear_params.hpp"

namespace wavebench::model {

class PowderBrake {
 public:
  explicit PowderBrake(const PowderBrakeParams& p);
  double rising_curve(double current) const noexcept;   // static torque, current rising
  double falling_curve(double current) const noexcept;  // static torque, current falling
  double capacity_rate(double capacity) const noexcept;
  double torque(double capacity, double omega) const noexcept;
  bool has_thermal_state() const noexcept { return p_.thermal_capacity > 0.0; }
  double temperature_rate(double temperature, double slip_power) const noexcept;
  const PowderBrakeParams& params() const noexcept { return p_; }

 private:
  PowderBrakeParams p_;
};

}  // namespace wavebench::model
