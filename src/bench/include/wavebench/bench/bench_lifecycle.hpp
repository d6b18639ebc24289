#pragma once
// The bench's lifecycle (after ros2_control's managed nodes), bench.md §7:
//   unconfigured  nothing connected
//   inactive      devices configured, SYNC, PDOs and heartbeats flowing, every channel readable,
//                 the drive's power stage off and the brake output off: where the daemon waits
//   active        the drive enabled for a run or a jog (and only then)
//   fault         tripped: the safe state held (brake off, drive quick-stopped or disabled)
//                 until an operator's reset brings it back to inactive
// connect(): unconfigured -> inactive; activate(): inactive -> active; deactivate(): active ->
// inactive; a trip: inactive/active -> fault; clear_fault(): fault -> inactive; disconnect():
// any -> unconfigured.

namespace wavebench::bench {

enum class BenchLifecycle { kUnconfigured, kInactive, kActive, kFault };

// Header-only, so the daemon's API names a state without linking the bench.
constexpr const char* lifecycle_name(BenchLifecycle state) {
  switch (state) {
    case BenchLifecycle::kUnconfigured:
      return "unconfigured";
    case BenchLifecycle::kInactive:
      return "inactive";
    case BenchLifecycle::kActive:
      return "active";
    case BenchLifecycle::kFault:
      return "fault";
  }
  return "?";
}
// Inactive or active: connected and not in fault.
constexpr bool operational(BenchLifecycle state) {
  return state == BenchLifecycle::kInactive || state == BenchLifecycle::kActive;
}

}  // namespace wavebench::bench
