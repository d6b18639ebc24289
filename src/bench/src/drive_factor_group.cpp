#include "wavebench/bench/drive_factor_group.hpp"

#include <cmath>
#include <cstdio>
#include <numbers>
#include <sstream>
#include <stdexcept>

namespace wavebench::bench {
namespace {

std::string hex(std::uint32_t v, int digits) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "0x%0*X", digits, v);
  return buf;
}

[[noreturn]] void refuse(const std::string& object, const std::string& value,
                         const std::string& expected) {
  throw std::invalid_argument("drive " + object + " = " + value + ": expected " + expected);
}

// A factor object as a ratio, after the checks a drive's answer must pass.
double ratio(const Fraction& f, std::uint16_t index, const char* name) {
  const auto check = [&](std::uint32_t v, int sub) {
    const std::string object = hex(index, 4) + (sub == 1 ? ":01 (" : ":02 (") + name +
                               (sub == 1 ? ", numerator)" : ", denominator)");
    if (v == 0) refuse(object, "0", "an UNSIGNED32 > 0");
    if (v >= 0x80000000U)
      refuse(object,
             std::to_string(v) + " (" + std::to_string(static_cast<std::int32_t>(v)) +
                 " as INTEGER32)",
             "a positive value below 2^31");
  };
  check(f.numerator, 1);
  check(f.denominator, 2);
  return static_cast<double>(f.numerator) / f.denominator;
}

struct SiUnit {
  int prefix = 0;         // 10^prefix
  std::uint8_t unit = 0;  // numerator unit
  std::uint8_t time = 0;  // denominator unit
};

SiUnit decode(std::uint32_t raw) {
  return {static_cast<std::int8_t>(raw >> 24), static_cast<std::uint8_t>(raw >> 16),
          static_cast<std::uint8_t>(raw >> 8)};
}

constexpr std::uint8_t kIncrement = 0xB5;

// Units of an angle per revolution; 0 for a unit that is not an angle.
double angle_units_per_rev(std::uint8_t unit) {
  switch (unit) {
    case 0x10:
      return 2 * std::numbers::pi;  // rad
    case 0x41:
      return 360;  // degree
    case 0x40:
      return 400;  // grade
    case 0x42:
      return 360 * 60;  // minute of arc
    case 0x43:
      return 360 * 3600;  // second of arc
    case 0xB4:
      return 1;  // revolution
    default:
      return 0;
  }
}

struct Factors {
  std::optional<double> position_encoder;  // increments per motor rev
  std::optional<double> velocity_encoder;  // increments/s per motor rev/s
  double gear = 1;                         // motor revs per driving shaft rev
  std::optional<double> feed;              // position units per driving shaft rev
};

// Units of `si` per motor revolution (the numerator part, before any time unit).
double per_motor_rev(const SiUnit& si, const std::optional<double>& increments, const Factors& f,
                     int feed_prefix, const std::string& object, std::string& how) {
  const double scale = std::pow(10.0, -si.prefix);
  if (si.unit == kIncrement) {
    if (!increments)
      refuse(object, "encoder increments",
             "a drive with its encoder resolution (0x608F/0x6090) to count them per revolution");
    how = "increments";
    return *increments * scale;
  }
  if (const double a = angle_units_per_rev(si.unit); a > 0) {
    how = "angle of the driving shaft / gear ratio";
    return a * scale / f.gear;
  }
  if (!f.feed)
    refuse(object, hex(si.unit, 2) + " (not an angle)",
           "an angle or increments, or a drive with a feed constant 0x6092");
  how = "feed constant / gear ratio";
  return *f.feed * std::pow(10.0, feed_prefix - si.prefix) / f.gear;
}

}  // namespace

FactorGroupUnits derive_factor_group_units(const DriveFactorGroup& g) {
  Factors f;
  std::ostringstream used;
  used.precision(10);
  if (g.position_encoder_resolution) {
    f.position_encoder =
        ratio(*g.position_encoder_resolution, 0x608F, "position encoder resolution");
    used << "0x608F " << *f.position_encoder << " inc/rev";
  }
  if (g.velocity_encoder_resolution) {
    f.velocity_encoder =
        ratio(*g.velocity_encoder_resolution, 0x6090, "velocity encoder resolution");
    used << (used.tellp() > 0 ? ", " : "") << "0x6090 " << *f.velocity_encoder << " inc/rev";
  }
  if (g.gear_ratio) {
    f.gear = ratio(*g.gear_ratio, 0x6091, "gear ratio");
    used << (used.tellp() > 0 ? ", " : "") << "0x6091 " << f.gear;
  }
  if (g.feed_constant) {
    f.feed = ratio(*g.feed_constant, 0x6092, "feed constant");
    used << (used.tellp() > 0 ? ", " : "") << "0x6092 " << *f.feed << " per shaft rev";
  }
  const auto velocity_increments = f.velocity_encoder ? f.velocity_encoder : f.position_encoder;

  FactorGroupUnits out;
  std::string position_how;
  int position_prefix = 0;
  bool position_in_increments = false;
  if (g.si_unit_position) {
    const auto si = decode(*g.si_unit_position);
    const std::string object = "0x60A8 (SI unit position)";
    if (si.time != 0)
      refuse(object, hex(*g.si_unit_position, 8), "a position unit (byte 1, time, = 0)");
    position_prefix = si.prefix;
    out.position_per_rev = per_motor_rev(si, f.position_encoder, f, 0, object, position_how);
    position_in_increments = si.unit == kIncrement;
    used << (used.tellp() > 0 ? ", " : "") << "0x60A8 " << hex(*g.si_unit_position, 8);
  } else if (f.feed) {
    out.position_per_rev = *f.feed / f.gear;
    position_how = "feed constant / gear ratio";
  } else if (f.position_encoder) {
    out.position_per_rev = *f.position_encoder;
    position_in_increments = true;
    position_how = "increments";
  } else {
    refuse("0x608F and 0x6092", "absent (SDO abort 06020000)",
           "a feed constant 0x6092, an encoder resolution 0x608F or an SI unit position 0x60A8 "
           "to derive the position unit from");
  }

  std::string velocity_how;
  if (g.si_unit_velocity) {
    const auto si = decode(*g.si_unit_velocity);
    const std::string object = "0x60A9 (SI unit velocity)";
    double per_second = 0;
    switch (si.time) {
      case 0x03:
        per_second = 1;
        break;
      case 0x47:
        per_second = 60;
        break;
      case 0x48:
        per_second = 3600;
        break;
      default:
        refuse(object, hex(*g.si_unit_velocity, 8),
               "a velocity unit per s (byte 1 = 0x03), min (0x47) or h (0x48)");
    }
    out.velocity_per_rev_s =
        per_motor_rev(si, velocity_increments, f, position_prefix, object, velocity_how) *
        per_second;
    velocity_how += per_second == 1 ? " per s" : per_second == 60 ? " per min" : " per h";
    used << (used.tellp() > 0 ? ", " : "") << "0x60A9 " << hex(*g.si_unit_velocity, 8);
  } else if (position_in_increments && f.velocity_encoder) {
    out.velocity_per_rev_s = *f.velocity_encoder;
    velocity_how = "velocity encoder increments per s";
  } else {
    out.velocity_per_rev_s = out.position_per_rev;
    velocity_how = "position units per s";
  }
  out.acceleration_per_rev_s2 = out.velocity_per_rev_s;

  std::ostringstream d;
  d.precision(10);
  d << "factor group (" << used.str() << "): position " << out.position_per_rev
    << " per motor rev (" << position_how << "), velocity " << out.velocity_per_rev_s
    << " per rev/s (" << velocity_how << "), acceleration velocity units per s";
  out.derivation = d.str();
  return out;
}

}  // namespace wavebench::bench
