#pragma once
// Heartbeat consumer for one node (CiA 301 §7.2.8.3.2): armed by the first heartbeat it sees,
// re-armed by every heartbeat after; silence past the consumer time raises the timeout event
// once, and the next heartbeat reports the node back.
//
// Judged by arrival, not by when the event loop gets to read a frame: the consumer time runs
// from each heartbeat's receive timestamp, and two heartbeats further apart than the consumer
// time are a loss even when both are read at once. When the timeout timer's handler runs late
// (the loop was held, and heartbeats that arrived meanwhile may still wait unread behind other
// frames), the verdict waits a short catch-up time in which the backlog is read; a heartbeat
// found there is judged by its timestamp. Loop latency thus neither raises nor hides a loss.

#include <boost/asio/steady_timer.hpp>
#include <chrono>
#include <functional>
#include <optional>

#include "wavebench/can/can_bus.hpp"
#include "wavebench/canopen/nmt.hpp"

namespace wavebench::canopen {

class HeartbeatConsumer {
 public:
  struct Hooks {
    std::function<void(NodeId, NmtState)> on_state;  // every change, boot-up included
    std::function<void(NodeId)> on_timeout;
    std::function<void(NodeId)> on_recovered;  // first heartbeat after a timeout
  };

  HeartbeatConsumer(can::CanBus& bus, NodeId node, std::chrono::milliseconds consumer_time,
                    Hooks hooks);
  ~HeartbeatConsumer();
  HeartbeatConsumer(const HeartbeatConsumer&) = delete;
  HeartbeatConsumer& operator=(const HeartbeatConsumer&) = delete;

  bool armed() const noexcept { return armed_; }
  bool timed_out() const noexcept { return timed_out_; }
  std::optional<NmtState> state() const noexcept { return state_; }
  std::uint64_t heartbeats() const noexcept { return count_; }
  // Verdicts deferred because the loop ran the timer late (see above).
  std::uint64_t late_verdicts_deferred() const noexcept { return deferred_; }

 private:
  using Clock = std::chrono::steady_clock;
  void on_frame(const can::Frame& frame) noexcept;
  void arm(Clock::time_point deadline) noexcept;
  void on_deadline(Clock::time_point deadline) noexcept;
  void raise_timeout() noexcept;

  NodeId node_;
  std::chrono::milliseconds consumer_time_;
  Hooks hooks_;
  boost::asio::steady_timer timer_;
  can::CanBus::Subscription subscription_;
  bool armed_ = false;
  bool timed_out_ = false;
  std::optional<NmtState> state_;
  std::uint64_t count_ = 0;
  std::uint64_t generation_ = 0;
  std::optional<std::chrono::system_clock::time_point> last_arrival_;
  int catch_ups_ = 0;  // consecutive deferred verdicts
  std::uint64_t deferred_ = 0;
};

}  // namespace wavebench::canopen
