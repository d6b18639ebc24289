#include "wavebench/simdevices/powder_brake_physics.hpp"

#include <algorithm>
#include <cmath>

namespace wavebench::simdevices {

PowderBrakePhysics::PowderBrakePhysics(PowderBrakeParams params)
    : params_(params), temperature_(params.ambient_c) {}

void PowderBrakePhysics::set_coil_current(double amps) noexcept {
  current_ = std::max(0.0, amps);
  const double i = coil_current();
  const double w = params_.hysteresis_a;
  if (i > effective_current_) {
    effective_current_ = i;
  } else if (i < effective_current_ - w) {
    effective_current_ = i + w;
  }
}

void PowderBrakePhysics::set_coil_open(bool open) noexcept {
  coil_open_ = open;
  set_coil_current(current_);
}

double PowderBrakePhysics::static_torque(double current) const noexcept {
  if (current < params_.threshold_current_a) return 0.0;
  const double k = params_.rated_torque_nm / params_.rated_current_a;
  return k * std::min(current, params_.rated_current_a);
}

double PowderBrakePhysics::current_for_torque(double torque) const noexcept {
  if (torque <= 0.0) return 0.0;
  const double k = params_.rated_torque_nm / params_.rated_current_a;
  return std::clamp(torque / k, params_.threshold_current_a, params_.rated_current_a);
}

double PowderBrakePhysics::current_for_torque_from_here(double torque) const noexcept {
  const double rising = current_for_torque(torque);
  if (rising >= effective_current_ || torque <= 0.0) return rising;
  return std::max(0.0, rising - params_.hysteresis_a);
}

bool PowderBrakePhysics::stopped() const noexcept {
  return std::abs(omega_) < params_.standstill_rad_per_s;
}

double PowderBrakePhysics::shaft_torque(double driving_torque) const noexcept {
  if (stopped()) return -std::clamp(driving_torque, -torque_, torque_);
  return omega_ > 0.0 ? -torque_ : torque_;
}

double PowderBrakePhysics::slip_power() const noexcept {
  return stopped() ? 0.0 : torque_ * std::abs(omega_);
}

void PowderBrakePhysics::step(double dt) noexcept {
  if (!(dt > 0.0)) return;
  // Heat first, from the torque held over the step's start (inputs constant over dt).
  const double i = coil_current();
  const double power = slip_power() + params_.coil_resistance_ohm * i * i;
  const double g = params_.heat_loss_w_per_k;
  const double c = params_.heat_capacity_j_per_k;
  if (g > 0.0) {
    const double equilibrium = params_.ambient_c + power / g;
    temperature_ = equilibrium + (temperature_ - equilibrium) * std::exp(-g * dt / c);
  } else {
    temperature_ += power * dt / c;
  }
  const double target = target_torque();
  const double tau = target > torque_ ? params_.tau_rise_s : params_.tau_fall_s;
  torque_ = target + (torque_ - target) * std::exp(-dt / tau);
}

}  // namespace wavebench::simdevices
