#pragma once
// Backlash dead zone g(Delta) (model.md §5) and the ElastoBacklash torque limit.
#include "wavebench/model/gear_params.hpp"

namespace wavebench::model {

struct DeadZoneValue {
  double x = 0;      // g(Delta), the twist the spring sees
  double slope = 0;  // g'(Delta), so x' = slope * Delta'
};

// Sharp: g = Delta -/+ b/2 outside |Delta| <= b/2, 0 inside. Smoothed (width eps > 0): the kink
// at each edge is replaced by a quadratic on [b/2 - eps/2, b/2 + eps/2], which keeps g odd,
// continuous and C1 and equal to the sharp form outside that band.
class BacklashDeadZone {
 public:
  BacklashDeadZone() = default;
  explicit BacklashDeadZone(const BacklashParams& params);

  DeadZoneValue evaluate(double delta) const noexcept;
  double half_width() const noexcept { return half_; }
  double smoothing() const noexcept { return eps_; }
  bool has_clearance() const noexcept { return half_ > 0.0 || eps_ > 0.0; }
  bool is_sharp() const noexcept { return eps_ == 0.0; }

 private:
  double half_ = 0;
  double eps_ = 0;
};

// Torque across a clearance from spring torque tau_c and damping torque tau_d, as Modelica's
// ElastoBacklash: no pulling torque (the sum never takes the sign opposite to the twist side)
// and the damping part never larger than the spring part. side = sign of the twist.
inline double limit_backlash_torque(double side, double tau_c, double tau_d) noexcept {
  if (side > 0.0) {
    if (tau_c + tau_d <= 0.0) return 0.0;
    return tau_c + (tau_d < tau_c ? tau_d : tau_c);
  }
  if (side < 0.0) {
    if (tau_c + tau_d >= 0.0) return 0.0;
    return tau_c + (tau_d > tau_c ? tau_d : tau_c);
  }
  return 0.0;
}

}  // namespace wavebench::model
