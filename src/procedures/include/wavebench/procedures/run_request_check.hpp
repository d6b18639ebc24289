#pragma once
// Checking a run request completely before anything is created or moves (issue #8): the CLI
// and the daemon refuse a bad request (exit 2, HTTP 400) before they open a store or start a
// run, and execute_run makes the same check before it creates the run folder.
//
// Checked, in order: every option's type and range and every list's length (the procedures'
// from_json); every brake torque the procedure will command against the bench's brake limits
// (the brake's own and safety.max_brake_torque); every input speed it will command against
// safety.max_input_speed; the run's estimated bench time against a bound; its estimated disk
// use against what is free on the runs folder's file system. A limit <= 0 is off.

#include <cstdint>
#include <filesystem>

#include "wavebench/bench/bench_description.hpp"
#include "wavebench/procedures/run_executor.hpp"
#include "wavebench/procedures/run_plan.hpp"

namespace wavebench::procedures {

// A bench shift: longer runs are a typo in a count or a speed, and they fill disks.
inline constexpr double kMaxRunBenchTimeS = 8 * 3600.0;

// What a run may take.
struct RunBudget {
  double max_bench_time_s = kMaxRunBenchTimeS;
  std::uint64_t free_disk_bytes = 0;  // for an unprivileged writer (statvfs f_bavail)
  std::filesystem::path runs_root;    // named in messages
};

// The budget under `runs_root`: the free space of the file system of its nearest existing
// ancestor (the root may not exist yet). Throws std::invalid_argument naming the path when
// even that cannot be examined.
RunBudget run_budget(const std::filesystem::path& runs_root);

// Throws std::invalid_argument naming the key, the value and what was expected, e.g.
// "static.loads_nm[1]: got '200', expected at most 95 N*m (the bench's brake limit)".
// Returns the run's estimate when it is accepted. `extra_channels`: how many the bench records
// beyond the core six (Bench::extra_channels().size(); a bench config's devices), each of
// which widens every sample log record.
RunEstimate check_run_request(const RunRequest& request, const bench::BenchDescription& bench,
                              std::size_t extra_channels, const RunBudget& budget);
RunEstimate check_run_request(const RunRequest& request, const bench::BenchDescription& bench,
                              std::size_t extra_channels, const std::filesystem::path& runs_root);

}  // namespace wavebench::procedures
