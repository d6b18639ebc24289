#include "wavebench/model/te_excitation.hpp"

#include <cmath>

#include "wavebench/model/angle_phasor.hpp"

namespace wavebench::model {
namespace {
// Beyond this many multiplications a phasor of the full argument is cheaper.
constexpr long kLongestPowerChain = 2;
}  // namespace

TeExcitation::TeExcitation(const std::vector<TeTerm>& terms) {
  for (const auto& t : terms) {
    if (t.amplitude_rad == 0.0) continue;
    if (!is_integer_order(t.order_input) || !is_integer_order(t.order_output)) {
      other_terms_.push_back({t.amplitude_rad, t.order_input, t.order_output, t.phase_rad});
      continue;
    }
    const auto a = static_cast<long>(t.order_input);
    const auto b = static_cast<long>(t.order_output);
    const Phasor phasor{t.amplitude_rad * std::cos(t.phase_rad),
                        t.amplitude_rad * std::sin(t.phase_rad)};
    bool merged = false;
    for (auto& it : integer_terms_) {
      if (it.order_input == a && it.order_output == b) {
        it.amplitude.re += phasor.re;
        it.amplitude.im += phasor.im;
        merged = true;
      }
    }
    if (!merged) integer_terms_.push_back({a, b, phasor});
  }
  for (const auto& t : integer_terms_) {
    if (std::abs(t.order_input) + std::abs(t.order_output) > kLongestPowerChain) continue;
    if (t.order_input != 0) uses_input_angle_ = true;
    if (t.order_output != 0) uses_output_angle_ = true;
  }
}

TeValue TeExcitation::evaluate(double theta1, double theta2, double omega1,
                               double omega2) const noexcept {
  TeValue v;
  if (!integer_terms_.empty()) {
    const Phasor z1 = uses_input_angle_ ? unit_phasor(theta1) : Phasor{};
    const Phasor z2 = uses_output_angle_ ? unit_phasor(theta2) : Phasor{};
    for (const IntegerTerm& t : integer_terms_) {
      Phasor p;
      if (std::abs(t.order_input) + std::abs(t.order_output) > kLongestPowerChain) {
        p = unit_phasor(static_cast<double>(t.order_input) * theta1 +
                        static_cast<double>(t.order_output) * theta2);
      } else {
        p = unit_power(z1, t.order_input);
        if (t.order_output != 0) p = p * unit_power(z2, t.order_output);
      }
      // (A e^(i phi)) e^(i arg): imaginary part A sin(arg + phi), real part A cos(arg + phi).
      const Phasor w = t.amplitude * p;
      v.value += w.im;
      v.rate += (static_cast<double>(t.order_input) * omega1 +
                 static_cast<double>(t.order_output) * omega2) *
                w.re;
    }
  }
  for (const Term& t : other_terms_) {
    const double arg = t.order_input * theta1 + t.order_output * theta2 + t.phase;
    v.value += t.amplitude * std::sin(arg);
    v.rate += t.amplitude * (t.order_input * omega1 + t.order_output * omega2) * std::cos(arg);
  }
  return v;
}

}  // namespace wavebench::model
