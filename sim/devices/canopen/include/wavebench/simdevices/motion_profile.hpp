#pragma once
// Online trapezoidal trajectory generator of a profile-mode drive: it moves a demand position
// and velocity toward a target with velocity, acceleration and deceleration limits, one
// control period at a time, and may be retargeted at any step (change set immediately, halt,
// quick stop).

namespace wavebench::simdevices {

class MotionProfile {
 public:
  void reset(double position, double velocity = 0) noexcept {
    position_ = position;
    velocity_ = velocity;
  }
  // One step toward `target`; returns true once the demand sits on the target at rest.
  bool step_to_position(double target, double max_velocity, double acceleration,
                        double deceleration, double dt) noexcept;
  // One step of the velocity toward `target_velocity` (accelerating or decelerating).
  void step_to_velocity(double target_velocity, double acceleration, double deceleration,
                        double dt) noexcept;

  double position() const noexcept { return position_; }
  double velocity() const noexcept { return velocity_; }

 private:
  double position_ = 0;
  double velocity_ = 0;
};

}  // namespace wavebench::simdevices
