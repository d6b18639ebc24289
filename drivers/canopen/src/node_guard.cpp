#include "wavebench/canopen/node_guard.hpp"

#include <stdexcept>
#include <string>

namespace wavebench::canopen {

can::Frame node_guard_request(NodeId node) {
  can::Frame f;
  f.id = heartbeat_cob_id(node);
  f.rtr = true;
  f.len = 1;  // the length of the answer asked for
  return f;
}

can::Frame node_guard_response(NodeId node, NmtState state, bool toggle) {
  return can::Frame::make(
      heartbeat_cob_id(node),
      {static_cast<std::uint8_t>(static_cast<std::uint8_t>(state) | (toggle ? 0x80U : 0x00U))});
}

NodeGuard::NodeGuard(NodeId node, std::chrono::milliseconds guard_time,
                     std::chrono::milliseconds life_time)
    : node_(node), guard_time_(guard_time), life_time_(life_time) {
  if (!valid_node(node))
    throw std::invalid_argument("node guarding: node id " + std::to_string(node) +
                                ": expected 1..127");
  if (guard_time.count() <= 0 || life_time < guard_time)
    throw std::invalid_argument("node guarding of node " + std::to_string(node) + ": guard time " +
                                std::to_string(guard_time.count()) + " ms, life time " +
                                std::to_string(life_time.count()) +
                                " ms: expected guard time > 0 and life time >= guard time");
}

void NodeGuard::start(Clock::time_point now) noexcept {
  next_poll_ = now;
  last_answer_ = now;
  unanswered_since_.reset();
  expected_toggle_.reset();
  toggle_failed_ = false;
}

void NodeGuard::polled(Clock::time_point now) noexcept {
  next_poll_ = now + guard_time_;
  if (!unanswered_since_) unanswered_since_ = now;
}

NodeGuard::Seen NodeGuard::on_frame(const can::Frame& frame, Clock::time_point now) noexcept {
  if (frame.id != heartbeat_cob_id(node_)) return Seen::none;
  const auto hb = decode_heartbeat(frame);
  if (!hb) return Seen::none;
  if (hb->state == NmtState::boot_up) {
    // The node (re)started: its toggle starts again at 0 (CiA 301).
    expected_toggle_ = false;
    state_ = hb->state;
    return Seen::boot_up;
  }
  state_ = hb->state;
  if (expected_toggle_ && *expected_toggle_ != hb->toggle) {
    ++toggle_errors_;
    toggle_failed_ = true;
    return Seen::toggle_error;
  }
  expected_toggle_ = !hb->toggle;
  ++answers_;
  last_answer_ = now;
  unanswered_since_.reset();
  return Seen::answer;
}

std::optional<NodeGuard::Lost> NodeGuard::lost(Clock::time_point now) const noexcept {
  if (toggle_failed_) return Lost{Lost::Why::toggle, now - last_answer_};
  if (unanswered_since_ && now - *unanswered_since_ > life_time_)
    return Lost{Lost::Why::silent, now - last_answer_};
  return std::nullopt;
}

}  // namespace wavebench::canopen
