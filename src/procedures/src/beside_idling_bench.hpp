#pragma once
// Post-run work (twin, its calibration, results, the report) takes seconds of CPU and disk.
// Done on the bench thread it would hold the bench's event loop: heartbeats would wait unread
// and then be judged stale all at once, SYNC and the live view would stop. So the work runs on
// a worker thread while the calling bench thread keeps the loop turning with idle_for(), at
// about real-time pace. The work must not call the bench.

#include <functional>

#include "wavebench/bench/bench.hpp"

namespace wavebench::procedures {

// Returns when `work` has returned; rethrows what it threw.
void run_beside_idling_bench(bench::Bench& bench, const std::function<void()>& work);

}  // namespace wavebench::procedures
