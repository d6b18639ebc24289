#include "wavebench/simdevices/powder_brake_physics.hpp"

#include <algorithm>
#include <cmath>

namespace wavebench::simdevices {

PowderBrakePhysics::PowderBrakePhysics(model::PowderBrakeParams params)
    : law_(params), temperature_(params.ambient_c) {}

void PowderBrakePhysics::set_coil_current(double amps) noexcept {
  current_ = std::max(0.0, amps);
  effective_current_ = law_.next_effective_current(effective_current_, coil_current());
}

void PowderBrakePhysics::set_coil_open(bool open) noexcept {
  coil_open_ = open;
  set_coil_current(current_);
}

bool PowderBrakePhysics::stopped() const noexcept {
  return std::abs(omega_) < params().standstill_rad_per_s;
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
  // Heat first, from the torque held over the step's start (inputs constant over dt): the
  // exact solution of the characteristic's C·dθ/dt = P − G·(θ − θ_ambient).
  if (law_.has_thermal_mass()) {
    const double power = slip_power();
    const double g = params().heat_loss_w_per_k;
    const double c = params().heat_capacity_j_per_k;
    if (g > 0.0) {
      const double equilibrium = params().ambient_c + power / g;
      temperature_ = equilibrium + (temperature_ - equilibrium) * std::exp(-g * dt / c);
    } else {
      temperature_ += power * dt / c;
    }
  }
  const double target = target_torque();
  torque_ = target + (torque_ - target) * std::exp(-dt / law_.lag_time_constant(target, torque_));
}

}  // namespace wavebench::simdevices
