#pragma once
// GET /api/live/stream: the live view as server-sent events. Each frame carries the samples
// that arrived since the last one, decimated by min and max per time column
// (analysis/min_max_columns.hpp; never every n-th), TE already in arcsec; every fifth frame
// also carries the daemon's status, so the page needs no polling.
//
//   data: {"seq": next sample seq, "missed": samples that left the buffer unsent,
//          "column_s": column width, "full_resolution": bool, "reset": bool,
//          "rows": {"t": [s], "te_arcsec": [...], "input_speed_rad_s": [...],
//                   "torque_nm": [...], "brake_current_a": [...]},   (null: no valid value)
//          "status": {... as GET /api/status ...}}                    (every fifth frame)
//
// Columns are aligned to multiples of column_s = window_s / columns and sent once complete,
// so a client appends rows and drops those older than window_s: the history it draws is the
// true envelope of every sample. `reset`: the time base went back (a new bench); start over.
// Reads LiveSampleBuffer (lock-free) on the HTTP side: the bench thread never waits for it.

#include <atomic>
#include <chrono>
#include <cstddef>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "wavebench/daemon/counted_slots.hpp"
#include "wavebench/daemon/event_stream.hpp"
#include "wavebench/daemon/http_target.hpp"
#include "wavebench/daemon/live_sample_buffer.hpp"

namespace wavebench::daemon {

struct LiveStreamParams {
  static constexpr double kMinWindowS = 1, kMaxWindowS = 600;
  static constexpr std::size_t kMinColumns = 10, kMaxColumns = 4000;
  double window_s = 60;
  std::size_t columns = 1000;
};

// window_s and columns from the query; std::invalid_argument naming key, value and range.
LiveStreamParams live_stream_params(const HttpTarget& target);

// At most DaemonApi::kMaxLiveStreams streams at once.
using LiveStreamClients = CountedSlots;

class LiveStreamFrames : public EventStream {
 public:
  static constexpr std::chrono::milliseconds kPeriod{40};  // 25 frames/s
  static constexpr int kStatusEvery = 5;

  // `status` gives GET /api/status's JSON; its "bench" ratio and direction_sign turn angles
  // into TE (null TE until a bench is described).
  LiveStreamFrames(const LiveSampleBuffer& live, std::function<nlohmann::json()> status,
                   LiveStreamParams params, std::shared_ptr<void> slot);

  std::chrono::milliseconds period() const override { return kPeriod; }
  std::optional<std::string> next() override;
  // The frame as JSON (next() sends it as one event); null when there is nothing to send.
  nlohmann::json frame();

 private:
  void take_sense(const nlohmann::json& status);

  const LiveSampleBuffer& live_;
  std::function<nlohmann::json()> status_;
  LiveStreamParams params_;
  std::shared_ptr<void> slot_;
  std::uint64_t next_seq_ = 0;
  long frames_ = 0;
  std::optional<double> ratio_;
  int direction_sign_ = 1;
  // Samples of columns not yet complete: t and the four series.
  std::vector<double> t_;
  std::vector<std::vector<double>> series_ = std::vector<std::vector<double>>(4);
};

}  // namespace wavebench::daemon
