#pragma once
// The one home of the angle units (issue #23): radians inside, arcsec/arcmin/degrees where users
// read them. Everything that converts an angle for a person or from a config uses these.

#include <numbers>

namespace wavebench::model {

inline constexpr double kRadPerDeg = std::numbers::pi / 180.0;
inline constexpr double kRadPerArcmin = std::numbers::pi / (180.0 * 60.0);
inline constexpr double kRadPerArcsec = std::numbers::pi / (180.0 * 3600.0);
inline constexpr double kDegPerRad = 180.0 / std::numbers::pi;
inline constexpr double kArcminPerRad = 180.0 * 60.0 / std::numbers::pi;
inline constexpr double kArcsecPerRad = 180.0 * 3600.0 / std::numbers::pi;

}  // namespace wavebench::model
