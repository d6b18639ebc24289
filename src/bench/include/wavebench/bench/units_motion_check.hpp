#pragma once
// The drive's units checked by a short, slow, bounded motion (issue #20), for a drive that does
// not state them (no 0x60A9): the input is turned slowly in profile velocity through the
// config's units, and the drive's own position (0x6064) and velocity (0x606C), read through the
// config's units, are compared with the travel the output encoder measures × N. A drive in
// other units than the config says reads a ratio far from 1 (rpm read as counts/s: 60/131072).
//
// Bounded whatever the drive's units: each cycle the encoder-measured input speed (over a 5 ms
// window) and travel are watched, and beyond `speed_bound` × the commanded speed or
// `travel_bound` × the intended travel the bench is stopped at once (request_stop: quick
// stop, brake safe); 5 ms, not the safety check's 8, to stop sooner. The drive is switched off
// afterwards however the motion ended, and a fault the bound caused is cleared (drive to Switch On
// Disabled); the brake is never energised. Runs on the bench thread, on a connected, inactive
// bench.

#include <string>

#include "wavebench/bench/bench.hpp"
#include "wavebench/bench/bench_config.hpp"

namespace wavebench::bench {

struct UnitsMotionOptions {
  double travel_rev = 0.1;  // intended input travel
  double speed_rpm = 10;    // commanded input speed, through the config's units
  double speed_bound = 3;   // × speed_rpm measured by the encoder: stop at once
  double travel_bound = 2;  // × travel_rev measured by the encoder: stop at once
  double min_ratio = 0.8;   // drive / encoder within [min_ratio, max_ratio]: the units agree
  double max_ratio = 1.25;
};

struct UnitsMotionResult {
  bool ok = false;
  bool bounded_stop = false;      // the speed or travel bound stopped it
  double encoder_travel_rad = 0;  // input travel measured by the output encoder × N
  double encoder_peak_rpm = 0;    // input speed measured by the output encoder × N
  double position_ratio = 0;      // drive's 0x6064 travel / encoder travel
  double velocity_ratio = 0;      // ∫ drive's 0x606C dt / encoder travel
  std::string detail;             // for the check's units row
};

UnitsMotionResult check_units_by_motion(Bench& bench, const DriveSettings& drive,
                                        const UnitsMotionOptions& options = {});

// The unit whose count per revolution (per rev/s) is nearest `per_rev` within 25 %, with the
// number, e.g. "rpm (54.21 per rev/s)"; otherwise the number alone ("1234 per rev/s").
std::string likely_drive_unit(double per_rev, double counts_per_revolution, bool velocity);

}  // namespace wavebench::bench
