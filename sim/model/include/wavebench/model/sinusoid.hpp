#pragma once
// offset + amplitude * sin(2 pi f t + phase), the time signal the drive, load and ripple use.
#include <cmath>
#include <numbers>

#include "wavebench/model/gear_params.hpp"

namespace wavebench::model {

inline double evaluate(const Sinusoid& s, double t) noexcept {
  if (s.amplitude == 0.0) return s.offset;
  return s.offset +
         s.amplitude * std::sin(2.0 * std::numbers::pi * s.frequency_hz * t + s.phase_rad);
}

}  // namespace wavebench::model
