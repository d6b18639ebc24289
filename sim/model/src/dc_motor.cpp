#include "wavebench/model/dc_motor.hpp"

#include <stdexcept>
#include <string>

#include "wavebench/model/sinusoid.hpp"

namespace wavebench::model {

DcMotor::DcMotor(const DcMotorInput& p) : p_(p) {
  if (!(p.resistance > 0)) {
    throw std::invalid_argument("input.resistance = " + std::to_string(p.resistance) +
                                " Ohm: expected > 0");
  }
  if (!(p.inductance >= 0)) {
    throw std::invalid_argument("input.inductance = " + std::to_string(p.inductance) +
                                " H: expected >= 0");
  }
}

double DcMotor::voltage(double t) const noexcept {
  return evaluate(p_.voltage, t);
}

double DcMotor::current_rate(double t, double current, double omega) const noexcept {
  return (voltage(t) - p_.resistance * current - p_.back_emf_constant * omega) / p_.inductance;
}

double DcMotor::algebraic_current(double t, double omega) const noexcept {
  return (voltage(t) - p_.back_emf_constant * omega) / p_.resistance;
}

}  // namespace wavebench::model
