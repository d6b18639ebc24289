#include "wavebench/model/powder_brake.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace wavebench::model {

namespace {
const PowderBrakeParams& checked(const PowderBrakeParams& p, double coil_current_a) {
  check_powder_brake_params(p);
  if (!(coil_current_a >= 0)) {
    throw std::invalid_argument("brake.current = " + std::to_string(coil_current_a) +
                                " A: expected >= 0");
  }
  return p;
}
}  // namespace

PowderBrake::PowderBrake(const PowderBrakeParams& p, double coil_current_a)
    : law_(checked(p, coil_current_a)),
      target_(law_.static_torque(law_.next_effective_current(0.0, coil_current_a))) {}

double PowderBrake::capacity_rate(double capacity) const noexcept {
  return (target_ - capacity) / law_.lag_time_constant(target_, capacity);
}

double PowderBrake::torque(double capacity, double omega) const noexcept {
  return capacity * std::tanh(omega / params().standstill_rad_per_s);
}

}  // namespace wavebench::model
