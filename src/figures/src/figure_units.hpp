#pragma once
// The units the declarations state figures in, as SI per unit (the angles from the one
// angle-units header).

#include "wavebench/model/angle_units.hpp"

namespace wavebench::figures::units {

inline constexpr double kArcmin = model::kRadPerArcmin;
inline constexpr double kArcsec = model::kRadPerArcsec;
inline constexpr double kNmPerRad = 1;

}  // namespace wavebench::figures::units
