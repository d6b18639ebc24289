#include "wavebench/model/lugre_friction.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace wavebench::model {

LuGre::LuGre(const LuGreFriction& p) : p_(p) {
  if (!(p.sigma0 > 0)) {
    throw std::invalid_argument("friction.sigma0 = " + std::to_string(p.sigma0) +
                                " N*m/rad: expected > 0");
  }
  if (!(p.coulomb > 0) || !(p.static_torque >= p.coulomb)) {
    throw std::invalid_argument("friction coulomb/static = " + std::to_string(p.coulomb) + "/" +
                                std::to_string(p.static_torque) +
                                " N*m: expected 0 < coulomb <= static");
  }
  if (!(p.stribeck_speed > 0)) {
    throw std::invalid_argument("friction.stribeck_speed = " + std::to_string(p.stribeck_speed) +
                                " rad/s: expected > 0");
  }
  inv_speed_sq_ = 1.0 / (p.stribeck_speed * p.stribeck_speed);
}

LuGreState LuGre::evaluate(double omega, double s) const noexcept {
  const double level =
      p_.coulomb + (p_.static_torque - p_.coulomb) * std::exp(-omega * omega * inv_speed_sq_);
  LuGreState st;
  st.bristle_rate = omega - std::abs(omega) * s * p_.sigma0 / level;
  st.torque = p_.sigma0 * s + p_.sigma1 * st.bristle_rate + p_.sigma2 * omega;
  st.dissipation = st.torque * omega - p_.sigma0 * s * st.bristle_rate;
  return st;
}

double LuGre::bristle_after(double omega, double s, double h) const noexcept {
  if (omega == 0.0) return s;
  const double level =
      p_.coulomb + (p_.static_torque - p_.coulomb) * std::exp(-omega * omega * inv_speed_sq_);
  const double rate = std::abs(omega) * p_.sigma0 / level;  // s' = omega - rate s
  const double steady = omega / rate;
  return steady + (s - steady) * std::exp(-rate * h);
}

double LuGre::steady_deflection() const noexcept {
  return p_.coulomb / p_.sigma0;
}

}  // namespace wavebench::model
