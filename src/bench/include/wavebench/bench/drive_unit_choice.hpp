#pragma once
// The drive's units as a bench config names them (`drive.position_unit`, `drive.velocity_unit`,
// `drive.acceleration_unit`): the motor encoder's counts (the default), a fixed unit with an
// optional decimal factor ("rpm", "0.1 rpm", "0.001 deg", "rad/s²"), or `factor_group`: read
// at connect from the drive's factor group and SI unit objects (drive_factor_group.hpp).

#include <string>

namespace wavebench::bench {

enum class DriveQuantity { kPosition, kVelocity, kAcceleration };

struct DriveUnitChoice {
  enum class Kind { kCounts, kFixed, kFactorGroup };
  Kind kind = Kind::kCounts;
  // kFixed: drive units per input revolution (per rev/s, per rev/s²).
  double per_rev = 0;
  std::string text = "counts";  // as written, for messages

  // Drive units per revolution (per rev/s, per rev/s²); counts are `counts_per_revolution`.
  // Not for kFactorGroup.
  double units_per_rev(double counts_per_revolution) const {
    return kind == Kind::kCounts ? counts_per_revolution : per_rev;
  }
};

// Throws std::invalid_argument saying what was expected (the caller names the key).
DriveUnitChoice parse_drive_unit(const std::string& text, DriveQuantity quantity);
// "counts, rev, deg, rad, with an optional factor (\"0.001 deg\"), or factor_group", ...
std::string expected_drive_units(DriveQuantity quantity);

}  // namespace wavebench::bench
