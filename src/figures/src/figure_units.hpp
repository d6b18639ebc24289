#pragma once
// The units the declarations state figures in, as SI per unit.

#include <numbers>

namespace wavebench::figures::units {

inline constexpr double kArcmin = std::numbers::pi / 10800;
inline constexpr double kArcsec = kArcmin / 60;
inline constexpr double kNmPerRad = 1;

}  // namespace wavebench::figures::units
