#include "wavebench/analysis/poincare_section.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace wavebench::analysis {

PoincareSection strobe_on_phase(std::span<const double> t, std::span<const double> phase,
                                std::span<const double> x, std::span<const double> v) {
  if (phase.size() != t.size() || x.size() != t.size() || v.size() != t.size()) {
    throw std::invalid_argument("Poincare section: t, phase, x and v differ in length");
  }
  PoincareSection section;
  if (t.size() < 2) return section;
  constexpr double kTwoPi = 2 * std::numbers::pi;
  const double direction = phase.back() >= phase.front() ? 1.0 : -1.0;
  // Index of the last multiple of 2 pi passed so far, in the direction of rotation.
  double next = direction > 0 ? std::floor(phase.front() / kTwoPi) + 1
                              : std::ceil(phase.front() / kTwoPi) - 1;
  for (std::size_t i = 1; i < t.size(); ++i) {
    while (direction * (phase[i] - next * kTwoPi) >= 0) {
      const double target = next * kTwoPi;
      const double span = phase[i] - phase[i - 1];
      const double u = span != 0 ? (target - phase[i - 1]) / span : 1.0;
      section.t.push_back(t[i - 1] + u * (t[i] - t[i - 1]));
      section.points.push_back(
          {x[i - 1] + u * (x[i] - x[i - 1]), v[i - 1] + u * (v[i] - v[i - 1])});
      next += direction;
    }
  }
  return section;
}

}  // namespace wavebench::analysis
