#pragma once
// DC motor drive (seed 003): T_m = K_m i - T_0, u = R i + L i' + K_e omega1. L = 0 makes the
// current algebraic, so no stiff electrical state appears.
#include "wavebench/model/gear_params.hpp"

namespace wavebench::model {

class DcMotor {
 public:
  explicit DcMotor(const DcMotorInput& p);
  bool has_current_state() const noexcept { return p_.inductance > 0.0; }
  double current_rate(double t, double current, double omega) const noexcept;
  double algebraic_current(double t, double omega) const noexcept;
  double torque(double current) const noexcept {
    return p_.torque_constant * current - p_.no_load_torque;
  }
  double voltage(double t) const noexcept;

 private:
  DcMotorInput p_;
};

}  // namespace wavebench::model
