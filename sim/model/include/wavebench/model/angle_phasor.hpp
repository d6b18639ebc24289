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

// a b + c; without -mfma std::fma would be a library call.
inline double fmadd(double a, double b, double c) noexcept {
  return a * b + c;
}

// cos and sin of one angle. libm's sincos was a third of the XB-80 run (three calls per
// right-hand side, arguments up to ~1e6 rad); this reduces by pi/2 in three parts of 33, 33
// and 53 bits (Cody-Waite: k times each of the first two is exact for |k| < 2^20) and sums the
// Taylor series to degree 15/16 on |r| <= pi/4, whose truncation error (pi/4)^17/17! = 4e-18
// is below a rounding. Larger arguments fall back to libm.
// Inlined so the independent phasors of one evaluation overlap in the pipeline.
[[gnu::always_inline]] inline Phasor unit_phasor(double angle) noexcept {
  if (!(std::abs(angle) < 1.6e6)) return {std::cos(angle), std::sin(angle)};
  constexpr double kTwoOverPi = 0.63661977236758134308;
  constexpr double kPio2Hi = 1.5707963267341256;      // pi/2 to 33 bits
  constexpr double kPio2Mid = 6.077100506303966e-11;  // the next 33 bits
  constexpr double kPio2Lo = 2.0222662487959506e-21;  // the rest
  // Round to nearest by truncation of +-0.5: a plain SSE2 conversion, where nearbyint would be a
  // library call without SSE4.1.
  const double q = angle * kTwoOverPi;
  const auto ki = static_cast<long long>(q + (q >= 0 ? 0.5 : -0.5));
  const auto k = static_cast<double>(ki);
  const double r = ((angle - k * kPio2Hi) - k * kPio2Mid) - k * kPio2Lo;
  const double r2 = r * r;
  // sin r = r (1 - r^2/3! + r^4/5! - ...), cos r = 1 - r^2/2! + r^4/4! - ...
  double s = -1.0 / 1307674368000.0;     // -1/15!
  s = fmadd(s, r2, 1.0 / 6227020800.0);  // 1/13!
  s = fmadd(s, r2, -1.0 / 39916800.0);   // -1/11!
  s = fmadd(s, r2, 1.0 / 362880.0);      // 1/9!
  s = fmadd(s, r2, -1.0 / 5040.0);       // -1/7!
  s = fmadd(s, r2, 1.0 / 120.0);         // 1/5!
  s = fmadd(s, r2, -1.0 / 6.0);          // -1/3!
  const double sin_r = fmadd(s * r2, r, r);
  double c = 1.0 / 20922789888000.0;       // 1/16!
  c = fmadd(c, r2, -1.0 / 87178291200.0);  // -1/14!
  c = fmadd(c, r2, 1.0 / 479001600.0);     // 1/12!
  c = fmadd(c, r2, -1.0 / 3628800.0);      // -1/10!
  c = fmadd(c, r2, 1.0 / 40320.0);         // 1/8!
  c = fmadd(c, r2, -1.0 / 720.0);          // -1/6!
  c = fmadd(c, r2, 1.0 / 24.0);            // 1/4!
  c = fmadd(c, r2, -0.5);                  // -1/2!
  const double cos_r = fmadd(c, r2, 1.0);
  switch (ki & 3) {
    case 0:
      return {cos_r, sin_r};
    case 1:
      return {-sin_r, cos_r};
    case 2:
      return {-cos_r, -sin_r};
    default:
      return {sin_r, -cos_r};
  }
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
