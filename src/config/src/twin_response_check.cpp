// A twin run whose response is not finite came from a case that is finite key by key but not
// together (a stiffness at its ceiling on a tiny inertia): refused like a bad value, naming the
// section whose keys drive the channel that went first, never written out as NaN plots.
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "wavebench/config/config_error.hpp"
#include "wavebench/config/twin_case.hpp"

namespace wavebench::config {

void check_finite_response(const model::SampledResponse& r) {
  // channel, the keys that set it
  const std::pair<const std::vector<double>*, const char*> channels[] = {
      {&r.twist, "stiffness (k0, k1, ...) against gear.inertia_input/inertia_output"},
      {&r.gear_torque, "stiffness (k0, k1, ...) and damping"},
      {&r.twist_rate, "damping and stiffness"},
      {&r.theta2_dev, "gear.inertia_output and load"},
      {&r.omega2, "gear.inertia_output and load"},
      {&r.alpha2, "gear.inertia_output and load"},
      {&r.load_torque, "load"},
      {&r.motor_torque, "input"},
      {&r.theta1, "input"},
      {&r.omega1, "input"},
      {&r.te, "te"},
  };
  std::size_t first = r.t.size();
  const char* keys = nullptr;
  for (const auto& [values, names] : channels) {
    for (std::size_t i = 0; i < values->size() && i < first; ++i) {
      if (!std::isfinite((*values)[i])) {
        first = i;
        keys = names;
        break;
      }
    }
  }
  if (keys == nullptr) return;
  char at[64];
  std::snprintf(at, sizeof at, "%.6g s", first < r.t.size() ? r.t[first] : 0.0);
  throw ConfigError(std::string(keys), std::string("a response that overflows at t = ") + at,
                    "values whose products stay finite (a lower stiffness or damping, a larger "
                    "inertia)");
}

}  // namespace wavebench::config
