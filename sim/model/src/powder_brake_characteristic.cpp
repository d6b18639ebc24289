#include "wavebench/model/powder_brake_characteristic.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace wavebench::model {

namespace {
std::string field(const char* name, double value) {
  return std::string("brake.") + name + " = " + std::to_string(value);
}
}  // namespace

void check_powder_brake_params(const PowderBrakeParams& p) {
  const auto require = [](bool ok, const char* name, double value, const char* expected) {
    if (!ok) throw std::invalid_argument(field(name, value) + ": expected " + expected);
  };
  require(p.rated_current_a > 0, "rated_current_a", p.rated_current_a, "> 0");
  require(p.rated_torque_nm >= 0, "rated_torque_nm", p.rated_torque_nm, ">= 0");
  require(p.threshold_current_a >= 0 && p.threshold_current_a < p.rated_current_a,
          "threshold_current_a", p.threshold_current_a, ">= 0 and below the rated current");
  require(p.hysteresis_a >= 0, "hysteresis_a", p.hysteresis_a, ">= 0");
  require(p.tau_rise_s > 0, "tau_rise_s", p.tau_rise_s, "> 0");
  require(p.tau_fall_s > 0, "tau_fall_s", p.tau_fall_s, "> 0");
  require(p.standstill_rad_per_s > 0, "standstill_rad_per_s", p.standstill_rad_per_s, "> 0");
  require(p.heat_capacity_j_per_k >= 0, "heat_capacity_j_per_k", p.heat_capacity_j_per_k,
          ">= 0 (0: no thermal model)");
  require(p.heat_loss_w_per_k >= 0, "heat_loss_w_per_k", p.heat_loss_w_per_k, ">= 0");
}

double PowderBrakeCharacteristic::static_torque(double effective_current) const noexcept {
  if (effective_current < p_.threshold_current_a) return 0.0;
  return torque_per_amp() * std::min(effective_current, p_.rated_current_a);
}

double PowderBrakeCharacteristic::next_effective_current(double effective,
                                                         double current) const noexcept {
  if (current > effective) return current;
  if (current < effective - p_.hysteresis_a) return current + p_.hysteresis_a;
  return effective;
}

double PowderBrakeCharacteristic::current_for_torque(double torque) const noexcept {
  if (torque <= 0.0) return 0.0;
  return std::clamp(torque / torque_per_amp(), p_.threshold_current_a, p_.rated_current_a);
}

double PowderBrakeCharacteristic::current_for_torque_from(double torque,
                                                          double effective) const noexcept {
  const double rising = current_for_torque(torque);
  if (rising >= effective || torque <= 0.0) return rising;
  return std::max(0.0, rising - p_.hysteresis_a);
}

}  // namespace wavebench::model
