#pragma once
// The drive's units as the drive itself states them, against the bench config (issue #20): a
// drive whose SI unit objects 0x60A8 (position) / 0x60A9 (velocity) name a unit other than the
// config's `drive.position_unit` / `drive.velocity_unit` would be commanded and read in the
// wrong unit (3000 rpm seen as 1.4 "counts/s"). The stated unit is made units per motor
// revolution by the factor group (drive_factor_group.hpp); a drive stating encoder increments
// without 0x608F/0x6090 is taken to count drive.counts_per_revolution of them per revolution.
// A config that says factor_group takes its units from the drive: nothing to compare.

#include <cstdint>
#include <string>

#include "wavebench/bench/bench_config.hpp"
#include "wavebench/bench/drive_factor_group.hpp"
#include "wavebench/canopen/sdo_client.hpp"

namespace wavebench::bench {

struct DriveUnitStatement {
  bool stated = false;  // the drive has 0x60A8 or 0x60A9 (and they could be made per revolution)
  bool agree = true;    // false: a stated unit disagrees with the config (more than 1 %)
  std::string detail;   // both sides named, e.g. "the drive says 0x60A9 = 0x00B44700 (rev/min),
                        // drive.velocity_unit = counts (increments/s)"
};

// "rev/min", "0.1 rev/min", "increments/s", "0.001 degree": an SI unit object's value in words.
std::string describe_si_unit(std::uint32_t raw);

DriveUnitStatement compare_drive_unit_statement(const DriveFactorGroup& drive,
                                                const DriveSettings& config);

// Reads 0x60A8, 0x60A9 and the factor group 0x608F..0x6092 by SDO; an object the drive lacks,
// or any failure to read it, leaves it unset (the statement is then what is left).
DriveFactorGroup read_drive_unit_statement(canopen::SdoClient& sdo);

}  // namespace wavebench::bench
