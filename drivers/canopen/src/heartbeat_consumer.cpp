#include "wavebench/canopen/heartbeat_consumer.hpp"

#include <algorithm>

namespace wavebench::canopen {
namespace {

// A timer handler later than this ran behind a held loop.
std::chrono::steady_clock::duration late_allowance(std::chrono::milliseconds consumer_time) {
  return std::max<std::chrono::steady_clock::duration>(consumer_time / 10,
                                                       std::chrono::milliseconds(2));
}

// Long enough to read a backlog of frames once the loop turns again; bounded so that a node
// that is really silent is reported at most a few of these late.
std::chrono::steady_clock::duration catch_up_time(std::chrono::milliseconds consumer_time) {
  return std::clamp<std::chrono::steady_clock::duration>(
      consumer_time / 4, std::chrono::milliseconds(5), std::chrono::milliseconds(100));
}

constexpr int kMaxCatchUps = 3;

}  // namespace

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
  const auto system_now = std::chrono::system_clock::now();
  const auto arrival = frame.timestamp.time_since_epoch().count() != 0
                           ? std::min(frame.timestamp, system_now)
                           : system_now;
  ++count_;
  // A gap the timer did not get to judge (both frames read late, or read during a catch-up).
  if (!timed_out_ && last_arrival_ && arrival - *last_arrival_ > consumer_time_) raise_timeout();
  if (!last_arrival_ || arrival > *last_arrival_) last_arrival_ = arrival;
  const bool recovered = timed_out_;
  timed_out_ = false;
  catch_ups_ = 0;
  const bool changed = !state_ || *state_ != hb->state;
  state_ = hb->state;
  // The consumer time runs from the arrival, on the steady clock of the timer.
  arm(Clock::now() - std::chrono::duration_cast<Clock::duration>(system_now - *last_arrival_) +
      consumer_time_);
  if (recovered && hooks_.on_recovered) hooks_.on_recovered(node_);
  if ((changed || hb->state == NmtState::boot_up) && hooks_.on_state) {
    hooks_.on_state(node_, hb->state);
  }
}

void HeartbeatConsumer::arm(Clock::time_point deadline) noexcept {
  armed_ = true;
  const auto generation = ++generation_;
  timer_.expires_at(deadline);
  timer_.async_wait([this, generation, deadline](const boost::system::error_code& ec) {
    if (ec == boost::asio::error::operation_aborted || generation != generation_) return;
    on_deadline(deadline);
  });
}

void HeartbeatConsumer::on_deadline(Clock::time_point deadline) noexcept {
  if (Clock::now() - deadline > late_allowance(consumer_time_) && catch_ups_ < kMaxCatchUps) {
    ++catch_ups_;
    ++deferred_;
    arm(Clock::now() + catch_up_time(consumer_time_));
    return;
  }
  catch_ups_ = 0;
  armed_ = false;
  raise_timeout();
}

void HeartbeatConsumer::raise_timeout() noexcept {
  timed_out_ = true;
  if (hooks_.on_timeout) hooks_.on_timeout(node_);
}

}  // namespace wavebench::canopen
