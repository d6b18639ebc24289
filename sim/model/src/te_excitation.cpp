#include "wavebench/model/te_excitation.hpp"

#include <cmath>

namespace wavebench::model {

TeExcitation::TeExcitation(const std::vector<TeTerm>& terms) {
  terms_.reserve(terms.size());
  for (const auto& t : terms) {
    if (t.amplitude_rad == 0.0) continue;
    terms_.push_back({t.amplitude_rad, t.order_input, t.order_output, t.phase_rad});
  }
}

TeValue TeExcitation::evaluate(double theta1, double theta2, double omega1,
                               double omega2) const noexcept {
  TeValue v;
  for (const Term& t : terms_) {
    const double arg = t.order_input * theta1 + t.order_output * theta2 + t.phase;
    const double s = std::sin(arg);
    const double c = std::cos(arg);
    v.value += t.amplitude * s;
    v.rate += t.amplitude * (t.order_input * omega1 + t.order_output * omega2) * c;
  }
  return v;
}

}  // namespace wavebench::model
