#include "wavebench/canopen/heartbeat_consumer.hpp"

namespace wavebench::canopen {

HeartbeatConsumer::HeartbeatConsumer(can::CanBus& bus, NodeId node,
                                     std::chrono::milliseconds consumer_time, Hooks hooks)
    : node_(node), consumer_time_(consumer_time), hooks_(std::move(hooks)), timer_(bus.context()) {
  if (!valid_node(node)) {
    throw std::invalid_argument("heartbeat consumer node id " + std::to_string(node) +
                                ": expected 1..127");
  }
  if (consumer_time.count() <= 0) {
    throw std::invalid_argument("heartbeat consumer time " + std::to_string(consumer_time.count()) +
                                " ms: expected > 0");
  }
  subscription_ = bus.on_frame([this](const can::Frame& f) { on_frame(f); });
}

HeartbeatConsumer::~HeartbeatConsumer() {
  subscription_.reset();
  timer_.cancel();
}

void HeartbeatConsumer::on_frame(const can::Frame& frame) noexcept {
  if (frame.id != heartbeat_cob_id(node_)) return;
  const auto hb = decode_heartbeat(frame);
  if (!hb) return;
  ++count_;
  const bool recovered = timed_out_;
  timed_out_ = false;
  const bool changed = !state_ || *state_ != hb->state;
  state_ = hb->state;
  arm();
  if (recovered && hooks_.on_recovered) hooks_.on_recovered(node_);
  if ((changed || hb->state == NmtState::boot_up) && hooks_.on_state) {
    hooks_.on_state(node_, hb->state);
  }
}

void HeartbeatConsumer::arm() noexcept {
  armed_ = true;
  const auto generation = ++generation_;
  timer_.expires_after(consumer_time_);
  timer_.async_wait([this, generation](const boost::system::error_code& ec) {
    if (ec == boost::asio::error::operation_aborted || generation != generation_) return;
    armed_ = false;
    timed_out_ = true;
    if (hooks_.on_timeout) hooks_.on_timeout(node_);
  });
}

}  // namespace wavebench::canopen
