#pragma once
// The drive's own units from its factor group and SI unit objects (CiA 402 / IEC 61800-7-201):
//
//   0x608F position encoder resolution  = encoder increments / motor revolutions
//   0x6090 velocity encoder resolution  = encoder increments per s / motor revolutions per s
//   0x6091 gear ratio                   = motor shaft revolutions / driving shaft revolutions
//   0x6092 feed constant                = feed (position units) / driving shaft revolutions
//   0x60A8, 0x60A9 SI unit position, velocity: prefix (10^n, byte 3, signed), unit (byte 2:
//          0x10 rad, 0x41 degree, 0x40 grade, 0x42 minute and 0x43 second of arc, 0xB4
//          revolution, 0xB5 encoder increment; other units are linear), time (byte 1: 0x03 s,
//          0x47 min, 0x48 h; 0 for position), byte 0 reserved
//
// Position units per motor revolution:
//   0x60A8 an angle  -> units per revolution of the driving shaft × 10^-prefix / gear ratio
//   0x60A8 increment -> 0x608F × 10^-prefix
//   otherwise        -> feed constant / gear ratio (position factor 0x6093 = 0x608F × gear /
//                       feed: the drive counts 0x608F increments per motor revolution, so a
//                       position unit is 0x608F / 0x6093 of them); without 0x6092: increments
// Velocity units per motor rev/s: the same with 0x60A9 (its increments those of 0x6090), times
// 60 or 3600 when its time is min or h; without 0x60A9: position units per second (velocity
// increments of 0x6090 where the position unit is the increment).
// Acceleration units per motor rev/s²: velocity units per second.

#include <cstdint>
#include <optional>
#include <string>

namespace wavebench::bench {

struct Fraction {
  std::uint32_t numerator = 0;    // sub-index 1
  std::uint32_t denominator = 0;  // sub-index 2
};

// As read from the drive; unset where the drive answered 06020000 (object does not exist).
struct DriveFactorGroup {
  std::optional<Fraction> position_encoder_resolution;  // 0x608F
  std::optional<Fraction> velocity_encoder_resolution;  // 0x6090
  std::optional<Fraction> gear_ratio;                   // 0x6091
  std::optional<Fraction> feed_constant;                // 0x6092
  std::optional<std::uint32_t> si_unit_position;        // 0x60A8
  std::optional<std::uint32_t> si_unit_velocity;        // 0x60A9
};

struct FactorGroupUnits {
  double position_per_rev = 0;         // drive position units per motor revolution
  double velocity_per_rev_s = 0;       // per motor rev/s
  double acceleration_per_rev_s2 = 0;  // per motor rev/s²
  std::string derivation;              // which objects gave them, for the log and the check
};

// Throws std::invalid_argument naming the object and sub-index, the value read and what was
// expected: a zero, a value that reads negative as INTEGER32 (>= 2^31), an unknown time unit,
// or an object the units need that the drive does not have.
FactorGroupUnits derive_factor_group_units(const DriveFactorGroup& group);

}  // namespace wavebench::bench
