#pragma once
// LuGre friction with bristle deflection s (model.md §6, seed 003):
//   s' = omega - |omega| s / g(omega),  g = (T_c + (T_s - T_c) exp(-(omega/omega_s)^2)) / sigma0
//   T_f = sigma0 s + sigma1 s' + sigma2 omega
#include "wavebench/model/gear_params.hpp"

namespace wavebench::model {

struct LuGreState {
  double bristle_rate = 0;  // s'
  double torque = 0;        // T_f
  double dissipation = 0;   // T_f omega minus the change of the bristle energy sigma0 s^2 / 2
};

class LuGre {
 public:
  explicit LuGre(const LuGreFriction& p);
  LuGreState evaluate(double omega, double s) const noexcept;
  double steady_deflection() const noexcept;  // T_c / sigma0, the bristle state's size
  // s after h at constant omega: the bristle equation is linear in s then, solved exactly, so
  // a fixed-step stepper stays stable however fast the bristles relax.
  double bristle_after(double omega, double s, double h) const noexcept;

 private:
  LuGreFriction p_;
  double inv_speed_sq_ = 0;
};

}  // namespace wavebench::model
