#include "wavebench/model/periodic_modulation.hpp"

#include <cmath>

namespace wavebench::model {

PeriodicModulation::PeriodicModulation(const std::vector<StiffnessHarmonic>& harmonics) {
  for (const auto& h : harmonics) {
    if (h.amplitude != 0.0) harmonics_.push_back(h);
  }
}

double PeriodicModulation::sum(double theta1, double theta2) const noexcept {
  double s = 0.0;
  for (const auto& h : harmonics_) {
    s += h.amplitude * std::cos(h.order_input * theta1 + h.order_output * theta2 + h.phase_rad);
  }
  return s;
}

}  // namespace wavebench::model
