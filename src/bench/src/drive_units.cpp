#include "wavebench/bench/drive_units.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>
#include <stdexcept>

namespace wavebench::bench {
namespace {

constexpr double kTwoPi = 2 * std::numbers::pi;

double positive(double v, const char* what) {
  if (!(v > 0) || !std::isfinite(v))
    throw std::invalid_argument(std::string("drive units: ") + what + " = " + std::to_string(v) +
                                ": expected a finite factor > 0");
  return v;
}

template <typename T>
T fit(double drive_value, const char* what, double si, const char* unit) {
  const double r = std::round(drive_value);
  if (!std::isfinite(r) || r > static_cast<double>(std::numeric_limits<T>::max()) ||
      r < static_cast<double>(std::numeric_limits<T>::min())) {
    std::ostringstream out;
    out << what << " = " << si << " " << unit << " is " << drive_value
        << " in the drive's units: outside the drive's "
        << (std::numeric_limits<T>::is_signed ? "INTEGER32" : "UNSIGNED32") << " range";
    throw std::invalid_argument(out.str());
  }
  return static_cast<T>(r);
}

}  // namespace

DriveUnits::DriveUnits(std::uint32_t counts_per_revolution)
    : DriveUnits(counts_per_revolution, counts_per_revolution, counts_per_revolution) {}

DriveUnits::DriveUnits(double position_per_rev, double velocity_per_rev_s,
                       double acceleration_per_rev_s2, double torque_nm_per_unit)
    : position_per_rad_(positive(position_per_rev, "position units per revolution") / kTwoPi),
      velocity_per_rad_s_(positive(velocity_per_rev_s, "velocity units per rev/s") / kTwoPi),
      acceleration_per_rad_s2_(positive(acceleration_per_rev_s2, "acceleration units per rev/s²") /
                               kTwoPi),
      torque_nm_per_unit_(torque_nm_per_unit) {}

std::int32_t DriveUnits::position_value(double rad, const char* what) const {
  return fit<std::int32_t>(rad * position_per_rad_, what, rad, "rad");
}

std::int32_t DriveUnits::velocity_value(double rad_s, const char* what) const {
  return fit<std::int32_t>(rad_s * velocity_per_rad_s_, what, rad_s, "rad/s");
}

std::uint32_t DriveUnits::acceleration_value(double rad_s2, const char* what) const {
  return std::max<std::uint32_t>(
      1, fit<std::uint32_t>(rad_s2 * acceleration_per_rad_s2_, what, rad_s2, "rad/s²"));
}

std::string DriveUnits::describe() const {
  std::ostringstream out;
  out.precision(10);
  out << "position " << position_per_rad_ * kTwoPi << " per rev, velocity "
      << velocity_per_rad_s_ * kTwoPi << " per rev/s, acceleration "
      << acceleration_per_rad_s2_ * kTwoPi << " per rev/s²";
  if (torque_nm_per_unit_ > 0) out << ", torque actual " << torque_nm_per_unit_ << " N*m per unit";
  return out.str();
}

}  // namespace wavebench::bench
