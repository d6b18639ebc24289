#include "wavebench/daemon/daemon_state.hpp"

namespace wavebench::daemon {

const char* daemon_state_name(DaemonState state) {
  switch (state) {
    case DaemonState::kIdle:
      return "idle";
    case DaemonState::kReady:
      return "ready";
    case DaemonState::kRunning:
      return "running";
    case DaemonState::kFault:
      return "fault";
    case DaemonState::kStopping:
      return "stopping";
  }
  return "?";
}

DaemonState daemon_state_of(bench::BenchLifecycle lifecycle, bool run_active) {
  switch (lifecycle) {
    case bench::BenchLifecycle::kFault:
      return DaemonState::kFault;
    case bench::BenchLifecycle::kUnconfigured:
      return DaemonState::kIdle;
    case bench::BenchLifecycle::kInactive:
    case bench::BenchLifecycle::kActive:
      break;
  }
  return run_active ? DaemonState::kRunning : DaemonState::kReady;
}

}  // namespace wavebench::daemon
