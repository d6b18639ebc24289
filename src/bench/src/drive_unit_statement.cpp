#include "wavebench/bench/drive_unit_statement.hpp"

#include <fmt/format.h>

#include <cmath>
#include <optional>
#include <stdexcept>

namespace wavebench::bench {
namespace {

std::string unit_name(std::uint8_t unit) {
  switch (unit) {
    case 0x10:
      return "rad";
    case 0x41:
      return "degree";
    case 0x40:
      return "grade";
    case 0x42:
      return "minute of arc";
    case 0x43:
      return "second of arc";
    case 0xB4:
      return "rev";
    case 0xB5:
      return "increments";
    case 0x01:
      return "m";
    default:
      return fmt::format("unit 0x{:02X}", unit);
  }
}

std::string time_name(std::uint8_t time) {
  switch (time) {
    case 0x00:
      return "";
    case 0x03:
      return "/s";
    case 0x47:
      return "/min";
    case 0x48:
      return "/h";
    default:
      return fmt::format("/time 0x{:02X}", time);
  }
}

// The config's unit in the words of describe_si_unit, e.g. "counts (increments/s)".
std::string config_words(const DriveUnitChoice& c, bool velocity) {
  if (c.kind == DriveUnitChoice::Kind::kCounts)
    return c.text + (velocity ? " (increments/s)" : " (increments)");
  return c.text;
}

struct Side {
  const char* object;  // "0x60A9"
  const char* key;     // "drive.velocity_unit"
  std::uint32_t raw;
  double drive_per_rev;   // stated unit per motor rev (rev/s)
  double config_per_rev;  // the config's
  const DriveUnitChoice* choice;
  bool velocity;
};

}  // namespace

std::string describe_si_unit(std::uint32_t raw) {
  const int prefix = static_cast<std::int8_t>(raw >> 24);
  const auto unit = static_cast<std::uint8_t>(raw >> 16);
  const auto time = static_cast<std::uint8_t>(raw >> 8);
  std::string scale;
  if (prefix != 0) scale = fmt::format("{:g} ", std::pow(10.0, prefix));
  return scale + unit_name(unit) + time_name(time);
}

DriveUnitStatement compare_drive_unit_statement(const DriveFactorGroup& drive,
                                                const DriveSettings& config) {
  DriveUnitStatement out;
  if (!drive.si_unit_position && !drive.si_unit_velocity) {
    out.detail = "the drive has no SI unit objects 0x60A8/0x60A9: it does not state its units";
    return out;
  }
  auto group = drive;
  // Increments without a stated resolution: the config's counts per revolution.
  const Fraction counts{config.counts_per_revolution, 1};
  if (!group.position_encoder_resolution) group.position_encoder_resolution = counts;
  FactorGroupUnits derived;
  try {
    derived = derive_factor_group_units(group);
  } catch (const std::invalid_argument& e) {
    out.detail =
        std::string("the drive's SI unit objects cannot be made per revolution: ") + e.what();
    return out;
  }
  out.stated = true;
  const double counts_per_rev = config.counts_per_revolution;
  using K = DriveUnitChoice::Kind;
  std::vector<Side> sides;
  if (drive.si_unit_position && config.position_unit.kind != K::kFactorGroup)
    sides.push_back({"0x60A8", "drive.position_unit", *drive.si_unit_position,
                     derived.position_per_rev, config.position_unit.units_per_rev(counts_per_rev),
                     &config.position_unit, false});
  if (drive.si_unit_velocity && config.velocity_unit.kind != K::kFactorGroup)
    sides.push_back({"0x60A9", "drive.velocity_unit", *drive.si_unit_velocity,
                     derived.velocity_per_rev_s, config.velocity_unit.units_per_rev(counts_per_rev),
                     &config.velocity_unit, true});
  std::string agreeing, disagreeing;
  for (const auto& s : sides) {
    const auto text =
        fmt::format("the drive says {} = 0x{:08X} ({}), {} = {}", s.object, s.raw,
                    describe_si_unit(s.raw), s.key, config_words(*s.choice, s.velocity));
    const double ratio = s.drive_per_rev / s.config_per_rev;
    if (std::abs(ratio - 1) <= 0.01) {
      agreeing += (agreeing.empty() ? "" : "; ") + text + ": they agree";
    } else {
      out.agree = false;
      disagreeing += (disagreeing.empty() ? "" : "; ") + text +
                     fmt::format(": a drive unit is {:.4g} of the config's", 1 / ratio);
    }
  }
  if (sides.empty()) {
    out.detail = "drive units from the drive's factor group (the config says factor_group)";
  } else {
    out.detail = out.agree ? agreeing : disagreeing;
  }
  return out;
}

DriveFactorGroup read_drive_unit_statement(canopen::SdoClient& sdo) {
  const auto read = [&](std::uint16_t index, std::uint8_t sub) -> std::optional<std::uint32_t> {
    std::error_code ec;
    const auto v = sdo.read<std::uint32_t>(index, sub, ec);
    if (ec) return std::nullopt;
    return v;
  };
  const auto fraction = [&](std::uint16_t index) -> std::optional<Fraction> {
    const auto num = read(index, 1);
    const auto den = num ? read(index, 2) : std::nullopt;
    if (!num || !den) return std::nullopt;
    return Fraction{*num, *den};
  };
  DriveFactorGroup g;
  g.si_unit_position = read(0x60A8, 0);
  g.si_unit_velocity = read(0x60A9, 0);
  if (!g.si_unit_position && !g.si_unit_velocity) return g;
  g.position_encoder_resolution = fraction(0x608F);
  g.velocity_encoder_resolution = fraction(0x6090);
  g.gear_ratio = fraction(0x6091);
  g.feed_constant = fraction(0x6092);
  return g;
}

}  // namespace wavebench::bench
