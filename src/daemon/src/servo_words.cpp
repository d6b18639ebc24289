#include "wavebench/daemon/servo_words.hpp"

#include <cmath>
#include <cstdio>
#include <numbers>

namespace wavebench::daemon {

namespace {

// Below this the input counts as standing (the bench's own stop test uses 0.5 rpm too).
constexpr double kStandingRpm = 0.5;

std::string fixed(double value, int digits) {
  char buffer[48];
  std::snprintf(buffer, sizeof buffer, "%.*f", digits, value);
  return buffer;
}

std::string servo_text(const BenchStatus& s, const std::optional<storage::SyncSample>& latest) {
  using bench::BenchLifecycle;
  switch (s.lifecycle) {
    case BenchLifecycle::kUnconfigured:
      return s.connect_error.empty() ? "not connected" : "not connected: " + s.connect_error;
    case BenchLifecycle::kFault:
      return "fault: " + s.fault_reason;
    case BenchLifecycle::kInactive:
    case BenchLifecycle::kActive:
      break;
  }
  const auto& drive_state = s.acquisition ? s.acquisition->drive_state : std::string();
  if (drive_state == "fault" || drive_state == "fault reaction active")
    return "fault: the servo drive reports a fault";
  if (s.lifecycle == BenchLifecycle::kInactive) return "servo off";
  if (s.manual.goto_deg) return "going to " + fixed(*s.manual.goto_deg, 1) + "°";
  if (latest && latest->valid(storage::kInputSpeedValid)) {
    const double rpm = latest->input_speed_rad_s * 60 / (2 * std::numbers::pi);
    if (std::abs(rpm) >= kStandingRpm) return "moving " + fixed(rpm, 0) + " rpm";
  }
  return "servo on, holding";
}

std::string brake_text(const BenchStatus& s, const std::optional<storage::SyncSample>& latest) {
  // The brake output is on only while the bench is active (bench.hpp); the controller's
  // readback confirms it, and may lag the lifecycle by a moment.
  const bool output_on = s.acquisition && s.acquisition->brake_output_on.value_or(false);
  if (!output_on || s.lifecycle != bench::BenchLifecycle::kActive) return "brake off";
  if (latest && latest->valid(storage::kBrakeTorqueValid))
    return "brake " + fixed(latest->brake_torque_nm, 1) + " N·m";
  return "brake on";
}

}  // namespace

ServoWords servo_words(const BenchStatus& status,
                       const std::optional<storage::SyncSample>& latest) {
  return {servo_text(status, latest), brake_text(status, latest)};
}

}  // namespace wavebench::daemon
