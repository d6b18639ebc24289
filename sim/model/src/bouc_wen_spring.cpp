#include "wavebench/model/bouc_wen_spring.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace wavebench::model {

BoucWenSpring::BoucWenSpring(const BoucWenStiffness& p) : p_(p) {
  if (!(p.k > 0)) {
    throw std::invalid_argument("stiffness.k = " + std::to_string(p.k) + " N*m/rad: expected > 0");
  }
  if (!(p.alpha >= 0 && p.alpha <= 1)) {
    throw std::invalid_argument("stiffness.alpha = " + std::to_string(p.alpha) +
                                ": expected 0 <= alpha <= 1");
  }
  if (!(p.n >= 1)) {
    throw std::invalid_argument("stiffness.n = " + std::to_string(p.n) + ": expected n >= 1");
  }
}

double BoucWenSpring::abs_pow_n(double w) const noexcept {
  const double a = std::abs(w);
  if (p_.n == 1.0) return a;
  if (p_.n == 2.0) return a * a;
  return std::pow(a, p_.n);
}

double BoucWenSpring::hysteretic_rate(double x_rate, double w) const noexcept {
  // |w|^(n-1) w = |w|^n sign(w)
  const double wn = abs_pow_n(w);
  const double sw = w < 0.0 ? -wn : wn;
  return x_rate - p_.beta * std::abs(x_rate) * sw - p_.gamma * x_rate * wn;
}

double BoucWenSpring::dissipation(double x_rate, double w) const noexcept {
  // (1-alpha) k w x' - d/dt[(1-alpha) k w^2/2] = (1-alpha) k w (x' - w')
  return (1.0 - p_.alpha) * p_.k * w * (x_rate - hysteretic_rate(x_rate, w));
}

}  // namespace wavebench::model
