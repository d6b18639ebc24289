#include "wavebench/model/coulomb_stribeck_friction.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace wavebench::model {

CoulombStribeck::CoulombStribeck(const CoulombStribeckFriction& p) : p_(p) {
  if (!(p.stribeck_speed > 0)) {
    throw std::invalid_argument("friction.stribeck_speed = " + std::to_string(p.stribeck_speed) +
                                " rad/s: expected > 0");
  }
  if (!(p.smoothing_speed > 0)) {
    throw std::invalid_argument("friction.smoothing_speed = " + std::to_string(p.smoothing_speed) +
                                " rad/s: expected > 0");
  }
}

double CoulombStribeck::torque(double omega) const noexcept {
  const double r = omega / p_.stribeck_speed;
  const double level = p_.coulomb + (p_.static_torque - p_.coulomb) * std::exp(-r * r);
  return level * std::tanh(omega / p_.smoothing_speed) + p_.viscous * omega;
}

}  // namespace wavebench::model
