#pragma once
// What the bench learns from the servo drive at configuration (issue #9): the drive's units
// (from the bench config, or its factor group where the config says factor_group) and which of
// the optional objects it uses the drive has. An optional object the drive answers with SDO
// abort 06020000 (object does not exist) becomes an absent channel: the bench goes on without
// it, names it, and refuses to connect only when a configured safety limit needs it.
//
//   drive.following_error  0x60F4 following error actual value (TPDO2 beside 0x606C)
//   drive.torque_actual    0x6077 torque actual value (scaled by 0x6076 or the config)

#include <string>
#include <vector>

#include "wavebench/bench/bench_config.hpp"
#include "wavebench/bench/bench_description.hpp"
#include "wavebench/bench/drive_units.hpp"
#include "wavebench/canopen/pdo_adoption.hpp"
#include "wavebench/canopen/sdo_client.hpp"

namespace wavebench::bench {

inline constexpr const char* kFollowingErrorChannel = "drive.following_error";
inline constexpr const char* kTorqueActualChannel = "drive.torque_actual";

struct AbsentChannel {
  std::string name;    // e.g. "drive.following_error"
  std::string reason;  // e.g. "0x60F4 (following error actual value): SDO abort 06020000 ..."
};

struct DriveChannels {
  DriveUnits units{131072};
  std::string units_origin;     // "bench config" or the factor group's derivation
  bool following_error = true;  // 0x60F4 mapped into TPDO2
  bool torque_actual = true;    // 0x6077 readable and scaled
  std::vector<AbsentChannel> absent;

  std::vector<std::string> absent_names() const;
};

// Reads the factor group and SI unit objects where a unit is factor_group, the rated torque
// 0x6076 where the torque scale is per mille of it, and probes 0x60F4 and 0x6077. Throws
// std::runtime_error naming the object and what was wrong (a bad factor, a transfer failing
// for another reason than a missing object), and naming both units when the drive's SI unit
// objects 0x60A8/0x60A9 state other units than the config's (drive_unit_statement.hpp).
DriveChannels read_drive_channels(canopen::SdoClient& sdo, const DriveSettings& settings);

// TPDO2: {0x606C, 0x60F4}, or {0x606C} where 0x60F4 is absent. A drive that refuses 0x60F4 in
// the mapping (06020000, or 06040041 not mappable) gets TPDO2 without it, and the channel
// becomes absent. A drive that refuses the mapping as such (read-only, canopen::
// is_fixed_mapping_refusal) has TPDO2 read back: fixed, used as found. Throws
// std::system_error when TPDO2 can neither be configured nor read back.
canopen::PdoAdoption map_drive_velocity_pdo(canopen::SdoClient& sdo, DriveChannels& channels);

// The units and where they came from (info), each absent channel with its reason (warning).
void log_drive_channels(const std::string& bench_name, const DriveChannels& channels);

// Throws std::runtime_error naming the limit and the absent channel it needs.
void check_limits_have_channels(const SafetyLimits& limits, const DriveChannels& channels);

}  // namespace wavebench::bench
