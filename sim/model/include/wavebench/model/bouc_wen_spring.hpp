#pragma once
// Form 7, Bouc-Wen: T = alpha k x + (1 - alpha) k w,
// w' = x' - beta |x'| |w|^(n-1) w - gamma x' |w|^n.
#include "wavebench/model/gear_params.hpp"

namespace wavebench::model {

class BoucWenSpring {
 public:
  explicit BoucWenSpring(const BoucWenStiffness& p);
  double torque(double x, double w) const noexcept {
    return p_.alpha * p_.k * x + (1.0 - p_.alpha) * p_.k * w;
  }
  double hysteretic_rate(double x_rate, double w) const noexcept;
  // Power lost in the hysteretic part: its work rate minus the change of (1-alpha) k w^2 / 2.
  double dissipation(double x_rate, double w) const noexcept;
  double small_twist_stiffness() const noexcept { return p_.k; }

 private:
  double abs_pow_n(double w) const noexcept;  // |w|^n
  BoucWenStiffness p_;
};

}  // namespace wavebench::model
