#include "wavebench/bench/node_guard_watch.hpp"

#include <cmath>

namespace wavebench::bench {

void NodeGuardWatch::add(canopen::NodeId node, std::chrono::milliseconds guard_time,
                         std::chrono::milliseconds life_time) {
  guards_.erase(node);
  guards_.emplace(node, canopen::NodeGuard(node, guard_time, life_time));
}

void NodeGuardWatch::start(Clock::time_point now) noexcept {
  for (auto& [node, g] : guards_) g.start(now);
}

void NodeGuardWatch::poll(can::CanBus& bus, Clock::time_point now) noexcept {
  for (auto& [node, g] : guards_) {
    if (!g.poll_due(now)) continue;
    std::error_code ec;
    bus.send(canopen::node_guard_request(node), ec);
    if (!ec) g.polled(now);
  }
}

std::optional<NodeGuardWatch::Answer> NodeGuardWatch::on_frame(const can::Frame& frame,
                                                               Clock::time_point now) noexcept {
  if (frame.rtr || frame.extended || frame.id <= canopen::kHeartbeatBase ||
      frame.id > canopen::kHeartbeatBase + 127)
    return std::nullopt;
  const auto it = guards_.find(static_cast<canopen::NodeId>(frame.id - canopen::kHeartbeatBase));
  if (it == guards_.end()) return std::nullopt;
  if (it->second.on_frame(frame, now) != canopen::NodeGuard::Seen::answer) return std::nullopt;
  return Answer{it->first, *it->second.state()};
}

std::optional<NodeGuardWatch::Lost> NodeGuardWatch::lost(Clock::time_point now) const noexcept {
  for (const auto& [node, g] : guards_) {
    if (const auto l = g.lost(now)) {
      return Lost{node, l->why == canopen::NodeGuard::Lost::Why::toggle,
                  std::chrono::duration<double>(l->silence).count(), g.guard_time(), g.life_time()};
    }
  }
  return std::nullopt;
}

std::string NodeGuardWatch::describe(const Lost& lost, const std::string& device) {
  const auto silent_ms = std::to_string(std::lround(lost.silent_s * 1e3));
  const auto times = "guard time " + std::to_string(lost.guard_time.count()) + " ms, life time " +
                     std::to_string(lost.life_time.count()) + " ms";
  std::string text = "node guarding of node " + std::to_string(lost.node) + " (" + device + ") ";
  if (lost.toggle)
    return text + "lost: the toggle bit of its answer did not alternate (last good answer " +
           silent_ms + " ms ago; " + times + ")";
  return text + "lost: no answer for " + silent_ms + " ms (" + times + ")";
}

const canopen::NodeGuard* NodeGuardWatch::guard(canopen::NodeId node) const {
  const auto it = guards_.find(node);
  return it == guards_.end() ? nullptr : &it->second;
}

std::vector<const canopen::NodeGuard*> NodeGuardWatch::all() const {
  std::vector<const canopen::NodeGuard*> out;
  for (const auto& [node, g] : guards_) out.push_back(&g);
  return out;
}

}  // namespace wavebench::bench
