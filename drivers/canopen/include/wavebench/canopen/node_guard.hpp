#pragma once
// Node guarding of one node by the master (CiA 301 §7.2.8.3.2.1), for a device without a
// heartbeat producer: the master sends a remote frame on 0x700 + node every guard time; the
// node answers one byte, bit 7 a toggle that alternates 0, 1, 0, ... (0 first after the node's
// boot-up or reset), bits 0..6 its NMT state. The node is lost when a request stays unanswered
// for the life time (guard time x life time factor), or when an answer's toggle does not
// alternate.
//
// Pure logic on the steady clock: the caller sends the request when poll_due() and hands every
// frame to on_frame(). The life time runs from the first request not answered yet, not from
// the last answer, so a loop held longer than the life time (no requests went out) is not a
// loss by itself; the silence reported is still the time since the last answer.

#include <chrono>
#include <cstdint>
#include <optional>

#include "wavebench/can/frame.hpp"
#include "wavebench/canopen/cob_id.hpp"
#include "wavebench/canopen/nmt.hpp"

namespace wavebench::canopen {

// The guard request: a remote frame on 0x700 + node asking for one byte.
can::Frame node_guard_request(NodeId node);
// The node's answer (what a simulated node sends).
can::Frame node_guard_response(NodeId node, NmtState state, bool toggle);

class NodeGuard {
 public:
  using Clock = std::chrono::steady_clock;

  // `life_time` is when an unanswered request makes the node lost (normally guard time x life
  // time factor; a caller may bound it further).
  NodeGuard(NodeId node, std::chrono::milliseconds guard_time, std::chrono::milliseconds life_time);

  // Guarding starts at `now`: the first request is due at once. The first answer after this
  // may carry either toggle (the node may have answered another master before); after a
  // boot-up message the next answer must carry toggle 0.
  void start(Clock::time_point now) noexcept;
  bool poll_due(Clock::time_point now) const noexcept { return now >= next_poll_; }
  // The request went out at `now`.
  void polled(Clock::time_point now) noexcept;
  // The caller's loop was held until `now` (it could neither send nor read): a request still
  // unanswered counts from now.
  void excuse(Clock::time_point now) noexcept {
    if (unanswered_since_ && *unanswered_since_ < now) unanswered_since_ = now;
  }

  enum class Seen { none, answer, boot_up, toggle_error };
  // Every frame from the bus; only this node's answers and boot-up messages count.
  Seen on_frame(const can::Frame& frame, Clock::time_point now) noexcept;

  struct Lost {
    enum class Why { silent, toggle } why;
    Clock::duration silence;  // since the last answer (or since start without one)
  };
  std::optional<Lost> lost(Clock::time_point now) const noexcept;

  NodeId node() const noexcept { return node_; }
  std::chrono::milliseconds guard_time() const noexcept { return guard_time_; }
  std::chrono::milliseconds life_time() const noexcept { return life_time_; }
  std::optional<NmtState> state() const noexcept { return state_; }
  std::uint64_t answers() const noexcept { return answers_; }
  std::uint64_t toggle_errors() const noexcept { return toggle_errors_; }
  Clock::duration silence(Clock::time_point now) const noexcept { return now - last_answer_; }

 private:
  NodeId node_;
  std::chrono::milliseconds guard_time_;
  std::chrono::milliseconds life_time_;
  Clock::time_point next_poll_{};
  Clock::time_point last_answer_{};
  std::optional<Clock::time_point> unanswered_since_;
  std::optional<bool> expected_toggle_;  // none: either is taken
  std::optional<NmtState> state_;
  bool toggle_failed_ = false;
  std::uint64_t answers_ = 0;
  std::uint64_t toggle_errors_ = 0;
};

}  // namespace wavebench::canopen
