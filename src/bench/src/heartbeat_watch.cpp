#include "wavebench/bench/heartbeat_watch.hpp"

#include <algorithm>

namespace wavebench::bench {
namespace {

double seconds(HeartbeatWatch::Clock::duration d) {
  return std::chrono::duration<double>(d).count();
}

// The node that sent a frame of the pre-defined connection set (EMCY, TPDO1..4, SDO answer);
// none for the master's own services and for heartbeats (seen() takes those).
std::optional<canopen::NodeId> sending_node(const can::Frame& f) {
  if (f.extended || f.rtr || f.error) return std::nullopt;
  const auto function = f.id & 0x780U;
  const auto node = static_cast<canopen::NodeId>(f.id & 0x7FU);
  if (node == 0) return std::nullopt;
  switch (function) {
    case 0x080:  // EMCY
    case 0x180:  // TPDO1..4
    case 0x280:
    case 0x380:
    case 0x480:
    case 0x580:  // SDO server -> client
      return node;
    default:
      return std::nullopt;
  }
}

}  // namespace

void HeartbeatWatch::seen(canopen::NodeId node, double now_s, Clock::time_point processed,
                          std::optional<canopen::NmtState> state) noexcept {
  const auto it = last_.find(node);
  if (it == last_.end()) return;
  auto& n = it->second;
  n.last_s = now_s;
  if (state) n.state = state;
  if (n.count > 0) n.largest_gap_s = std::max(n.largest_gap_s, seconds(processed - n.processed));
  n.processed = processed;
  n.any_frame = std::max(n.any_frame, processed);
  ++n.count;
}

void HeartbeatWatch::frame(const can::Frame& frame, Clock::time_point processed) noexcept {
  const auto node = sending_node(frame);
  if (!node) return;
  const auto it = last_.find(*node);
  if (it != last_.end()) it->second.any_frame = std::max(it->second.any_frame, processed);
}

bool HeartbeatWatch::silent(const Node& n, double now_s, Clock::time_point wall) const noexcept {
  if (timeout_s_ <= 0 || seconds(wall - std::max(n.processed, resumed_)) <= timeout_s_)
    return false;
  if (!simulated_) return true;
  // Simulated clock: the heartbeat is overdue in bench time too, or the node is mute.
  return now_s - n.last_s > timeout_s_ ||
         seconds(wall - std::max(n.any_frame, resumed_)) > timeout_s_;
}

std::optional<HeartbeatWatch::Lost> HeartbeatWatch::lost(double now_s,
                                                         Clock::time_point wall) const noexcept {
  for (const auto& [node, n] : last_)
    if (silent(n, now_s, wall)) return Lost{node, seconds(wall - n.processed)};
  return std::nullopt;
}

bool HeartbeatWatch::missing(canopen::NodeId node, double now_s,
                             Clock::time_point wall) const noexcept {
  const auto it = last_.find(node);
  return it != last_.end() && silent(it->second, now_s, wall);
}

std::uint64_t HeartbeatWatch::count(canopen::NodeId node) const noexcept {
  const auto it = last_.find(node);
  return it == last_.end() ? 0 : it->second.count;
}

double HeartbeatWatch::largest_gap(canopen::NodeId node) const noexcept {
  const auto it = last_.find(node);
  return it == last_.end() ? 0 : it->second.largest_gap_s;
}

std::vector<HeartbeatWatch::NodeView> HeartbeatWatch::nodes(Clock::time_point wall) const {
  std::vector<NodeView> out;
  out.reserve(last_.size());
  for (const auto& [node, n] : last_)
    out.push_back({node, n.state, seconds(wall - n.processed), n.count});
  return out;
}

}  // namespace wavebench::bench
