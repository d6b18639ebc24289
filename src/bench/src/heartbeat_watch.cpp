#include "wavebench/bench/heartbeat_watch.hpp"

#include <algorithm>

namespace wavebench::bench {

void HeartbeatWatch::seen(canopen::NodeId node, double now_s, Clock::time_point processed,
                          std::optional<canopen::NmtState> state) noexcept {
  const auto it = last_.find(node);
  if (it == last_.end()) return;
  auto& n = it->second;
  n.last_s = now_s;
  if (state) n.state = state;
  if (n.processed != Clock::time_point{})
    n.largest_gap_s =
        std::max(n.largest_gap_s, std::chrono::duration<double>(processed - n.processed).count());
  n.processed = processed;
  ++n.count;
}

std::optional<HeartbeatWatch::Lost> HeartbeatWatch::lost(double now_s) const noexcept {
  if (timeout_s_ <= 0) return std::nullopt;
  for (const auto& [node, n] : last_)
    if (now_s - n.last_s > timeout_s_) return Lost{node, now_s - n.last_s};
  return std::nullopt;
}

bool HeartbeatWatch::missing(canopen::NodeId node, double now_s) const noexcept {
  const auto it = last_.find(node);
  return timeout_s_ > 0 && it != last_.end() && now_s - it->second.last_s > timeout_s_;
}

std::uint64_t HeartbeatWatch::count(canopen::NodeId node) const noexcept {
  const auto it = last_.find(node);
  return it == last_.end() ? 0 : it->second.count;
}

double HeartbeatWatch::largest_gap(canopen::NodeId node) const noexcept {
  const auto it = last_.find(node);
  return it == last_.end() ? 0 : it->second.largest_gap_s;
}

std::vector<HeartbeatWatch::NodeView> HeartbeatWatch::nodes(double now_s) const {
  std::vector<NodeView> out;
  out.reserve(last_.size());
  for (const auto& [node, n] : last_) out.push_back({node, n.state, now_s - n.last_s, n.count});
  return out;
}

}  // namespace wavebench::bench
