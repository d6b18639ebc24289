#pragma once
// The servo and the brake in the words an operator reads (issue #21): "servo off", "servo on,
// holding", "moving 30 rpm", "going to 12.0°", "fault: ..."; "brake off", "brake 5.0 N·m".
// From the bench lifecycle, the drive's CiA 402 state, the manual panel and the newest sample,
// so /api/status never makes an operator decode a statusword.

#include <optional>
#include <string>

#include "wavebench/daemon/bench_thread.hpp"
#include "wavebench/storage/sync_sample.hpp"

namespace wavebench::daemon {

struct ServoWords {
  std::string servo;
  std::string brake;
};

ServoWords servo_words(const BenchStatus& status, const std::optional<storage::SyncSample>& latest);

}  // namespace wavebench::daemon
