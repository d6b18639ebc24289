#pragma once
// exp(i (a theta1 + b theta2)) for integer orders from exp(i theta1) and exp(i theta2): one
// sincos per shaft angle instead of one per term. The TE lines of interest have integer orders
// (up to U z_C = 540), and sincos of those large arguments dominated the model's cost.
#include <cmath>

namespace wavebench::model {

// A unit phasor as (cos, sin); multiplied by hand because std::complex's operator* checks for
// NaN/inf operands on every call (C99 Annex G), which is wasted on unit-length values.
struct Phasor {
  double re = 1.0, im = 0.0;
  Phasor operator*(const Phasor& o) const noexcept {
    return {re * o.re - im * o.im, re * o.im + im * o.re};
  }
};

inline Phasor unit_phasor(double angle) noexcept {
  return {std::cos(angle), std::sin(angle)};
}

inline Phasor unit_power(Phasor z, long n) noexcept {
  Phasor result;
  const bool invert = n < 0;
  unsigned long m = static_cast<unsigned long>(invert ? -n : n);
  while (m != 0) {
    if (m & 1UL) result = result * z;
    z = z * z;
    m >>= 1;
  }
  if (invert) result.im = -result.im;  // |z| = 1: the inverse is the conjugate
  return result;
}

inline bool is_integer_order(double order) noexcept {
  return std::abs(order) < 1e6 && order == std::round(order);
}

}  // namespace wavebench::model
