#pragma once
// A CiA 402 style servo drive: position loop (P) -> speed command (limited) -> velocity loop
// (PI) -> torque command (limited). The integrator is frozen while the torque saturates in
// the direction it would push further (conditional integration against wind-up, PiController).
#include "wavebench/model/gear_params.hpp"
#include "wavebench/model/pi_controller.hpp"

namespace wavebench::model {

struct ServoOutput {
  double torque = 0;         // [N*m]
  double integral_rate = 0;  // d/dt of the integrated speed error [rad/s]
};

class ServoDrive {
 public:
  explicit ServoDrive(const ServoDriveInput& p);
  bool has_integral_state() const noexcept { return p_.velocity_integral_time > 0.0; }
  ServoOutput evaluate(double theta1, double omega1, double integral) const noexcept;
  double speed_command(double theta1) const noexcept;

 private:
  ServoDriveInput p_;
  PiController position_loop_;  // P: position error -> speed command
  PiController velocity_loop_;  // PI: speed error -> torque, integral owned by the solver
};

}  // namespace wavebench::model
