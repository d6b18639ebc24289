#pragma once
// Quantities in configs: a plain number is SI; a string carries a unit ("8 arcmin",
// "2680 rpm", "0.2839 kg*m^2"). Every key declares its dimension, so a unit of the wrong kind
// is caught where it is written, not as a wrong result later.

#include <string>
#include <string_view>
#include <vector>

namespace wavebench::strict_yaml {

enum class Dimension {
  kDimensionless,
  kAngle,               // rad
  kAngularSpeed,        // rad/s ("Hz" here means rev/s)
  kLength,              // m
  kTorque,              // N*m
  kStiffness,           // N*m/rad
  kQuadraticStiffness,  // N*m/rad^2
  kCubicStiffness,      // N*m/rad^3
  kInertia,             // kg*m^2
  kDamping,             // N*m*s/rad
  kTime,                // s
  kFrequency,           // Hz
  kRate,                // 1/s (decay rates, loop gains)
  kCurrent,             // A
  kVoltage,             // V
  kResistance,          // Ohm
  kInductance,          // H
  kTorqueConstant,      // N*m/A
  kBackEmfConstant,     // V*s/rad
  kTemperature,         // degC
  kHeatCapacity,        // J/K
  kThermalResistance,   // K/W
};

// "a stiffness (N*m/rad, N*m/arcmin, N*m/arcsec, ...)": used in error messages.
std::string describe(Dimension dimension);

// The units a dimension accepts, as written in configs.
std::vector<std::string> accepted_units(Dimension dimension);

// Parses "<number> [unit]" into SI. Throws RefusedConfig naming `key` (and `source`) on an
// unknown unit, a unit of another dimension, a malformed number or a non-finite value.
double parse_quantity(std::string_view text, Dimension dimension, const std::string& key,
                      const std::string& source = {});

// A plain number already in SI: only checked for finiteness.
double checked_si(double value, const std::string& key);

}  // namespace wavebench::strict_yaml
