#pragma once
// Form 6 (seed 003, time-invariant): T = a x^3 + b x^2 + c x + z with z' = A x' - B z, i.e.
// z = integral of A e^(-B(t - tau)) x'(tau) dtau. The memory stores z^2 / (2A) and dissipates
// B z^2 / A, which is what the energy account books.
#include "wavebench/model/gear_params.hpp"

namespace wavebench::model {

class FadingMemorySpring {
 public:
  explicit FadingMemorySpring(const FadingMemoryStiffness& p) : p_(p) {}
  double torque(double x, double z) const noexcept {
    return ((p_.a * x + p_.b) * x + p_.c) * x + z;
  }
  double memory_rate(double x_rate, double z) const noexcept {
    return p_.memory_gain * x_rate - p_.memory_decay * z;
  }
  double dissipation(double z) const noexcept {
    return p_.memory_gain > 0.0 ? p_.memory_decay * z * z / p_.memory_gain : 0.0;
  }
  double small_twist_stiffness() const noexcept { return p_.c + p_.memory_gain; }

 private:
  FadingMemoryStiffness p_;
};

}  // namespace wavebench::model
