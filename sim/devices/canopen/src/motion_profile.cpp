#include "wavebench/simdevices/motion_profile.hpp"

#include <algorithm>
#include <cmath>

namespace wavebench::simdevices {

void MotionProfile::step_to_velocity(double target_velocity, double acceleration,
                                     double deceleration, double dt) noexcept {
  const double v = velocity_;
  // Slowing down (toward zero, or through it) uses the deceleration.
  const bool slowing = (v > 0 && target_velocity < v) || (v < 0 && target_velocity > v);
  const double rate = (slowing ? deceleration : acceleration) * dt;
  double next = v;
  if (target_velocity > v) {
    next = std::min(target_velocity, v + rate);
  } else {
    next = std::max(target_velocity, v - rate);
  }
  position_ += 0.5 * (v + next) * dt;
  velocity_ = next;
}

bool MotionProfile::step_to_position(double target, double max_velocity, double acceleration,
                                     double deceleration, double dt) noexcept {
  const double remaining = target - position_;
  const double step_dec = deceleration * dt;
  if (std::abs(remaining) <= 0.5 * step_dec * dt + 1e-9 && std::abs(velocity_) <= step_dec) {
    position_ = target;
    velocity_ = 0;
    return true;
  }
  // The fastest speed from which the deceleration still stops on the target, corrected for
  // the discrete step so that the demand does not overshoot.
  const double braking = -0.5 * step_dec + std::sqrt(0.25 * step_dec * step_dec +
                                                     2 * deceleration * std::abs(remaining));
  const double desired = std::copysign(std::min(max_velocity, braking), remaining);
  step_to_velocity(desired, acceleration, deceleration, dt);
  const double after = target - position_;
  if ((after == 0 || std::signbit(after) != std::signbit(remaining)) &&
      std::abs(velocity_) <= 2 * step_dec) {
    position_ = target;
    velocity_ = 0;
    return true;
  }
  return false;
}

}  // namespace wavebench::simdevices
