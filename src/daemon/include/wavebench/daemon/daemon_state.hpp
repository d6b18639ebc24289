#pragma once
// The daemon's state as operators see it (issue #5): from the bench lifecycle and whether a run
// is active.

#include "wavebench/bench/bench.hpp"

namespace wavebench::daemon {

enum class DaemonState {
  kIdle,      // no bench connected (not yet, or connecting failed)
  kReady,     // bench connected, no run
  kRunning,   // a run is active
  kFault,     // bench tripped: safe state held until reset
  kStopping,  // an operator stop: safe state held, back to ready on its own (no reset)
};

const char* daemon_state_name(DaemonState state);
// A tripped bench shows kFault even while its run is still winding down.
DaemonState daemon_state_of(bench::BenchLifecycle lifecycle, bool run_active);

}  // namespace wavebench::daemon
