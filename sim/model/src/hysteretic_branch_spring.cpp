#include "wavebench/model/hysteretic_branch_spring.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "wavebench/model/angle_units.hpp"

namespace wavebench::model {
namespace {

// Integral of (A|s|^2 + B|s| + C) ds from 0 to x (x in arcsec): odd in x.
double branch_integral(double a, double b, double c, double x_rad) noexcept {
  const double x = x_rad * kArcsecPerRad;
  const double m = std::abs(x);
  const double v = ((a / 3.0 * m + 0.5 * b) * m + c) * m;
  return x < 0.0 ? -v : v;
}

}  // namespace

HystereticBranchSpring::HystereticBranchSpring(const HystereticBranchStiffness& p) : p_(p) {
  if (!(p.c_load > 0) || !(p.c_unload > 0)) {
    throw std::invalid_argument(
        "stiffness hysteretic c_load/c_unload = " + std::to_string(p.c_load) + "/" +
        std::to_string(p.c_unload) + " N*m/arcsec: expected both > 0");
  }
}

double HystereticBranchSpring::loading_integral(double x) const noexcept {
  return branch_integral(p_.a_load, p_.b_load, p_.c_load, x);
}

double HystereticBranchSpring::unloading_integral(double x) const noexcept {
  return branch_integral(p_.a_unload, p_.b_unload, p_.c_unload, x);
}

double HystereticBranchSpring::torque(double x, const BranchAnchor& anchor) const noexcept {
  if (anchor.loading) return anchor.torque + loading_integral(x) - loading_integral(anchor.x);
  return anchor.torque + unloading_integral(x) - unloading_integral(anchor.x);
}

double HystereticBranchSpring::small_twist_stiffness() const noexcept {
  return p_.c_load * kArcsecPerRad;
}

}  // namespace wavebench::model
