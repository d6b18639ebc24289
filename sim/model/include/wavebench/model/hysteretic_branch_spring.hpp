#pragma once
// Form 5 (seed 001): loading stiffness K2(x) while |torque| rises, unloading K1(x) while it
// falls, x in arcsec, K in N*m/arcsec evaluated at |x| so the curves are odd. The torque
// follows the active branch's integral from the last switch point (a reversal of the twist
// direction or a torque zero crossing), which the model keeps as discrete state, so loops close.
#include "wavebench/model/gear_params.hpp"

namespace wavebench::model {

struct BranchAnchor {
  double x = 0;       // twist at the last switch [rad]
  double torque = 0;  // torque there [N*m]
  bool loading = true;
};

class HystereticBranchSpring {
 public:
  explicit HystereticBranchSpring(const HystereticBranchStiffness& p);
  double torque(double x, const BranchAnchor& anchor) const noexcept;
  // Integral of the branch stiffness from 0 to x [N*m]; odd in x.
  double loading_integral(double x) const noexcept;
  double unloading_integral(double x) const noexcept;
  double small_twist_stiffness() const noexcept;  // C2 per rad
  // Which branch follows a switch: loading iff the torque moves away from zero.
  static bool loading_after(double torque, double direction) noexcept {
    return torque * direction > 0.0 || torque == 0.0;
  }

 private:
  HystereticBranchStiffness p_;
};

}  // namespace wavebench::model
