#pragma once
// The commissioning check (`wavebench bench check`, GET /api/bench/check): nothing moves
// (unless CheckOptions::motion asks for the units check's bounded motion), the devices stay
// inactive (drive power stage off, brake output off). One row per device and item:
// EDS agreement, node answers, device type, identity, each used object (an SDO upload: present,
// its size matching its type; nothing is written but what connecting writes), PDO mapping read
// back, heartbeat seen, SYNC round trip, bus load at the SYNC rate, brake registers readable,
// drive units. Runs on the bench thread.

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "wavebench/bench/canopen_bench.hpp"

namespace wavebench::bench {

struct CheckRow {
  std::string device;  // "servo drive (node 1)", "brake controller", "bus"
  std::string item;    // "identity", "0x6041:0 statusword", ...
  bool ok = false;
  std::string detail;  // what was seen; for a red row, what is wrong
};

struct CheckReport {
  std::string bench;
  std::vector<CheckRow> rows;
  bool all_green() const;
};

struct CheckOptions {
  // Connect an unconfigured bench for the rows that need PDOs flowing (the CLI); the daemon's
  // bench is connected already. A bench the check connected is left connected (inactive).
  bool connect = true;
  double observe_s = 0;  // heartbeat/SYNC window; 0: 3 heartbeat periods, at least 100 SYNCs
  // Issue #20: where the drive does not state its velocity unit (no 0x60A9), turn the input
  // a short, slow, bounded way (units_motion_check.hpp) to compare the drive's units with the
  // encoders. Only on an inactive bench; off by default (the check then moves nothing).
  bool motion = false;
};

CheckReport check_bench(CanopenBench& bench, const CheckOptions& options = {});

std::string format_check_table(const CheckReport& report);
nlohmann::json check_report_json(const CheckReport& report);

}  // namespace wavebench::bench
