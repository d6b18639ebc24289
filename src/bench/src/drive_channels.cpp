#include "wavebench/bench/drive_channels.hpp"

#include <spdlog/spdlog.h>

#include <cmath>
#include <cstdio>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "wavebench/bench/cia402_drive_device.hpp"
#include "wavebench/bench/drive_factor_group.hpp"
#include "wavebench/bench/drive_unit_statement.hpp"
#include "wavebench/canopen/pdo.hpp"
#include "wavebench/canopen/sdo_abort.hpp"

namespace wavebench::bench {
namespace {

using canopen::SdoAbort;

std::string hex4(std::uint16_t index) {
  char buf[8];
  std::snprintf(buf, sizeof buf, "0x%04X", index);
  return buf;
}

bool object_missing(const std::error_code& ec) {
  return ec == make_error_code(SdoAbort::no_object) ||
         ec == make_error_code(SdoAbort::no_sub_index);
}

std::string abort_reason(std::uint16_t index, const char* name, const std::error_code& ec) {
  char code[16];
  std::snprintf(code, sizeof code, "%08X", canopen::abort_code_of(ec));
  return hex4(index) + " (" + name + "): SDO abort " + code + " (" + ec.message() + ")";
}

// A value the drive may lack: unset on 06020000 / 06090011, thrown on any other failure.
template <typename T>
std::optional<T> read_optional(canopen::SdoClient& sdo, std::uint16_t index, std::uint8_t sub,
                               const char* name, std::error_code* missing = nullptr) {
  std::error_code ec;
  const T v = sdo.read<T>(index, sub, ec);
  if (!ec) return v;
  if (object_missing(ec)) {
    if (missing) *missing = ec;
    return std::nullopt;
  }
  throw std::runtime_error("reading " + hex4(index) + ":" + std::to_string(sub) + " (" + name +
                           "): " + ec.message());
}

std::optional<Fraction> read_fraction(canopen::SdoClient& sdo, std::uint16_t index,
                                      const char* name) {
  const auto num = read_optional<std::uint32_t>(sdo, index, 1, name);
  if (!num) return std::nullopt;
  const auto den = read_optional<std::uint32_t>(sdo, index, 2, name);
  if (!den)
    throw std::runtime_error(hex4(index) + " (" + name +
                             ") has sub-index 1 but not 2: expected both (numerator, denominator)");
  return Fraction{*num, *den};
}

bool any_factor_group(const DriveSettings& s) {
  using K = DriveUnitChoice::Kind;
  return s.position_unit.kind == K::kFactorGroup || s.velocity_unit.kind == K::kFactorGroup ||
         s.acceleration_unit.kind == K::kFactorGroup;
}

}  // namespace

std::vector<std::string> DriveChannels::absent_names() const {
  std::vector<std::string> out;
  for (const auto& a : absent) out.push_back(a.name);
  return out;
}

DriveChannels read_drive_channels(canopen::SdoClient& sdo, const DriveSettings& settings) {
  DriveChannels c;
  const double counts = settings.counts_per_revolution;
  double position = 0, velocity = 0, acceleration = 0;
  std::string origin = "bench config (position " + settings.position_unit.text + ", velocity " +
                       settings.velocity_unit.text + ", acceleration " +
                       settings.acceleration_unit.text + ")";
  if (any_factor_group(settings)) {
    DriveFactorGroup g;
    g.position_encoder_resolution = read_fraction(sdo, 0x608F, "position encoder resolution");
    g.velocity_encoder_resolution = read_fraction(sdo, 0x6090, "velocity encoder resolution");
    g.gear_ratio = read_fraction(sdo, 0x6091, "gear ratio");
    g.feed_constant = read_fraction(sdo, 0x6092, "feed constant");
    g.si_unit_position = read_optional<std::uint32_t>(sdo, 0x60A8, 0, "SI unit position");
    g.si_unit_velocity = read_optional<std::uint32_t>(sdo, 0x60A9, 0, "SI unit velocity");
    try {
      const auto derived = derive_factor_group_units(g);
      position = derived.position_per_rev;
      velocity = derived.velocity_per_rev_s;
      acceleration = derived.acceleration_per_rev_s2;
      origin += ", " + derived.derivation;
    } catch (const std::invalid_argument& e) {
      throw std::runtime_error(std::string("units from the factor group: ") + e.what());
    }
  }
  using K = DriveUnitChoice::Kind;
  if (settings.position_unit.kind != K::kFactorGroup)
    position = settings.position_unit.units_per_rev(counts);
  if (settings.velocity_unit.kind != K::kFactorGroup)
    velocity = settings.velocity_unit.units_per_rev(counts);
  if (settings.acceleration_unit.kind != K::kFactorGroup)
    acceleration = settings.acceleration_unit.units_per_rev(counts);
  c.units = DriveUnits(position, velocity, acceleration);
  c.units_origin = origin;
  // Issue #20: a drive stating other units (0x60A8/0x60A9) than the config would be commanded
  // and read in the wrong ones (a run at 2185× the speed, its speed limit blinded): no connect.
  if (const auto stated = compare_drive_unit_statement(read_drive_unit_statement(sdo), settings);
      !stated.agree)
    throw std::runtime_error("drive units: " + stated.detail +
                             ": set the config's drive units to the drive's (or factor_group)");

  std::error_code missing;
  if (!read_optional<std::int32_t>(sdo, 0x60F4, 0, "following error actual value", &missing)) {
    c.following_error = false;
    c.absent.push_back(
        {kFollowingErrorChannel, abort_reason(0x60F4, "following error actual value", missing)});
  }
  if (!read_optional<std::int16_t>(sdo, 0x6077, 0, "torque actual value", &missing)) {
    c.torque_actual = false;
    c.absent.push_back(
        {kTorqueActualChannel, abort_reason(0x6077, "torque actual value", missing)});
  } else if (settings.torque_actual_nm_per_unit) {
    c.units.set_torque_nm_per_unit(*settings.torque_actual_nm_per_unit);
  } else if (const auto rated =
                 read_optional<std::uint32_t>(sdo, 0x6076, 0, "motor rated torque", &missing)) {
    if (*rated == 0)
      throw std::runtime_error(
          "0x6076 (motor rated torque) = 0 mN*m: expected > 0 to scale torque actual 0x6077 (per "
          "mille of it), or drive.torque_actual_scale in the bench config");
    c.units.set_torque_nm_per_unit(*rated * 1e-6);  // mN·m, per mille
  } else {
    c.torque_actual = false;
    c.absent.push_back(
        {kTorqueActualChannel, abort_reason(0x6076, "motor rated torque", missing) +
                                   ": 0x6077 has no scale; drive.torque_actual_scale gives one"});
  }
  return c;
}

canopen::PdoAdoption map_drive_velocity_pdo(canopen::SdoClient& sdo, DriveChannels& channels) {
  using canopen::PdoDirection;
  const auto wanted = Cia402DriveDevice::velocity_pdo(sdo.node(), channels.following_error);
  std::error_code ec;
  canopen::configure_pdo(sdo, PdoDirection::transmit, 2, wanted, ec);
  if (!ec) return {PdoDirection::transmit, 2, wanted, false, {}};
  if (channels.following_error &&
      (object_missing(ec) || ec == make_error_code(SdoAbort::not_mappable))) {
    // Refused for 0x60F4, perhaps not for the mapping as such: TPDO2 without it.
    auto without = canopen::configure_or_read_back(
        sdo, PdoDirection::transmit, 2, Cia402DriveDevice::velocity_pdo(sdo.node(), false));
    if (!without.fixed) {
      channels.following_error = false;
      channels.absent.push_back(
          {kFollowingErrorChannel,
           abort_reason(0x60F4, "following error actual value", ec) + " when mapped into TPDO2"});
    }
    return without;
  }
  if (!canopen::is_fixed_mapping_refusal(ec))
    throw std::system_error(ec, "TPDO2 of node " + std::to_string(sdo.node()));
  return canopen::read_back_refused(sdo, PdoDirection::transmit, 2, ec);
}

void log_drive_channels(const std::string& bench_name, const DriveChannels& channels) {
  spdlog::info("bench '{}': servo drive units: {} [{}]", bench_name, channels.units.describe(),
               channels.units_origin);
  for (const auto& absent : channels.absent)
    spdlog::warn("bench '{}': channel {} absent: {}", bench_name, absent.name, absent.reason);
}

void check_limits_have_channels(const SafetyLimits& limits, const DriveChannels& channels) {
  if (limits.max_following_error_rad > 0 && !channels.following_error) {
    std::ostringstream out;
    out << "safety.max_following_error (" << limits.max_following_error_rad
        << " rad) needs the following error, but channel " << kFollowingErrorChannel
        << " is absent";
    for (const auto& a : channels.absent)
      if (a.name == kFollowingErrorChannel) out << " (" << a.reason << ")";
    out << ": leave the limit out of the bench config for this drive";
    throw std::runtime_error(out.str());
  }
}

}  // namespace wavebench::bench
