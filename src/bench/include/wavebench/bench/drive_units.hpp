#pragma once
// The one place where the servo drive's units become SI (issue #9): position (0x6064, 0x607A,
// 0x60F4), velocity (0x606C, 0x60FF, 0x6081), acceleration (0x6083, 0x6084) and torque actual
// (0x6077) in the drive's units, against the input (motor) shaft's rad, rad/s, rad/s² and N·m.
// Built from the bench config's drive units (drive_unit_choice.hpp) and, where the config says
// factor_group, from the drive's factor group read at connect (drive_factor_group.hpp).

#include <cstdint>
#include <string>

namespace wavebench::bench {

class DriveUnits {
 public:
  // Increments of the motor encoder, increments/s and increments/s² (the bench's first units).
  explicit DriveUnits(std::uint32_t counts_per_revolution);
  // Drive units per input revolution, per rev/s and per rev/s², each > 0; N·m per unit of torque
  // actual (0: not known). Throws std::invalid_argument on a factor that is not > 0 and finite.
  DriveUnits(double position_per_rev, double velocity_per_rev_s, double acceleration_per_rev_s2,
             double torque_nm_per_unit = 0);

  double angle(double position) const noexcept { return position / position_per_rad_; }
  double speed(double velocity) const noexcept { return velocity / velocity_per_rad_s_; }
  double torque_nm(double torque_actual) const noexcept {
    return torque_actual * torque_nm_per_unit_;
  }
  double position_per_rad() const noexcept { return position_per_rad_; }
  double velocity_per_rad_s() const noexcept { return velocity_per_rad_s_; }
  double acceleration_per_rad_s2() const noexcept { return acceleration_per_rad_s2_; }
  double torque_nm_per_unit() const noexcept { return torque_nm_per_unit_; }
  void set_torque_nm_per_unit(double nm_per_unit) noexcept { torque_nm_per_unit_ = nm_per_unit; }

  // The drive's value for an SI one, rounded; throws std::invalid_argument naming `what`, the
  // value and the range when it does not fit the object's type.
  std::int32_t position_value(double rad, const char* what) const;    // INTEGER32
  std::int32_t velocity_value(double rad_s, const char* what) const;  // INTEGER32
  // UNSIGNED32, at least 1: a drive may refuse an acceleration of 0.
  std::uint32_t acceleration_value(double rad_s2, const char* what) const;

  // E.g. "position 131072 per rev, velocity 60 per rev/s, acceleration 60 per rev/s², torque
  // actual 0.0013 N*m per unit", for the connect log and the commissioning check.
  std::string describe() const;

 private:
  double position_per_rad_;
  double velocity_per_rad_s_;
  double acceleration_per_rad_s2_;
  double torque_nm_per_unit_;
};

}  // namespace wavebench::bench
