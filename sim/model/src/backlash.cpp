#include "wavebench/model/backlash.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace wavebench::model {

BacklashDeadZone::BacklashDeadZone(const BacklashParams& params)
    : half_(0.5 * params.total_rad), eps_(params.smoothing_rad) {
  if (!(params.total_rad >= 0.0)) {
    throw std::invalid_argument("backlash.total = " + std::to_string(params.total_rad) +
                                " rad: expected >= 0");
  }
  if (!(params.smoothing_rad >= 0.0) || params.smoothing_rad > params.total_rad) {
    throw std::invalid_argument("backlash.smoothing = " + std::to_string(params.smoothing_rad) +
                                " rad: expected 0 <= smoothing <= total backlash (" +
                                std::to_string(params.total_rad) + " rad)");
  }
}

DeadZoneValue BacklashDeadZone::evaluate(double delta) const noexcept {
  const double a = std::abs(delta);
  const double sign = delta < 0.0 ? -1.0 : 1.0;
  if (eps_ == 0.0) {
    if (a <= half_) return {0.0, 0.0};
    return {delta - sign * half_, 1.0};
  }
  const double inner = half_ - 0.5 * eps_;
  const double outer = half_ + 0.5 * eps_;
  if (a <= inner) return {0.0, 0.0};
  if (a >= outer) return {delta - sign * half_, 1.0};
  // Quadratic blend: value 0 and slope 0 at the inner edge, value eps/2 and slope 1 at the
  // outer edge, where the sharp form is |Delta| - b/2 = eps/2.
  const double u = a - inner;
  return {sign * u * u / (2.0 * eps_), u / eps_};
}

}  // namespace wavebench::model
