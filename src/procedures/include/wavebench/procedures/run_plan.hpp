#pragma once
// What a procedure will command and how long it will take, worked out from its options and the
// bench before anything moves (issue #8): the run request check holds every brake torque and
// input speed against the bench's safety limits, and the bench time and disk use against the
// run's bounds. Each procedure's plan() follows its run() step by step, so the two change
// together.

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "wavebench/bench/bench_description.hpp"

namespace wavebench::procedures {

// One value a procedure will command, as the request gave it.
struct CommandedValue {
  std::string key;        // as named in messages: "static.loads_nm[1]", "dynamic.input_rpm"
  double given = 0;       // in the option's own unit
  std::string unit;       // of `given`: "N*m", "rad/s", "rpm"
  double per_unit = 1.0;  // SI (N·m, rad/s of the input) per unit of `given`
  double si() const { return given * per_unit; }
};

struct RunPlan {
  std::vector<CommandedValue> brake_torques_nm;    // every brake setpoint other than release
  std::vector<CommandedValue> input_speeds_rad_s;  // every input speed (moves, runs, approaches)
  double bench_time_s = 0;                         // estimated
  std::string duration_terms;  // what the estimate is made of, with the keys that drive it
  // Why run() would refuse these options on this bench, when it would; checked after the
  // limits so that an over-limit value is named first.
  std::string refusal;
};

// A profile move of the input over `distance_rad` at `speed_rad_s`: trapezoidal at a nominal
// drive acceleration, plus the target-reached handshake.
double planned_move_s(double distance_rad, double speed_rad_s);
// Starting or stopping a velocity run at `speed_rad_s`.
double planned_ramp_s(double speed_rad_s);

// What a run will write: samples.wbs at one record per SYNC (its size grows with the bench's
// extra channels, Bench::extra_channels()), twin.csv (one text row per sample) when the twin runs,
// and a fixed margin for results.json, the report and its plots, status.json and the index row.
struct RunEstimate {
  double bench_time_s = 0;
  std::uint64_t samples = 0;
  std::uint64_t sample_log_bytes = 0;
  std::uint64_t twin_bytes = 0;
  std::uint64_t other_bytes = 0;
  std::uint64_t disk_bytes() const { return sample_log_bytes + twin_bytes + other_bytes; }
};

inline constexpr std::uint64_t kTwinCsvBytesPerSample = 256;  // 13 columns of %.9g and commas
inline constexpr std::uint64_t kRunMarginBytes = 32ull << 20;

RunEstimate estimate_run(const RunPlan& plan, const bench::BenchDescription& bench,
                         std::size_t extra_channels, bool twin);

}  // namespace wavebench::procedures
