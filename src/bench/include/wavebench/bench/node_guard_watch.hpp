#pragma once
// The bench's node guarding (CiA 301 §7.2.8.3.2.1) of the nodes that have no heartbeat producer:
// one canopen::NodeGuard per guarded node, on the wall (steady) clock whatever the bench clock
// (a simulated node answers a remote frame at once, without bench time passing). The bench
// calls poll() from its loop (a timer) and hands it every frame; lost() is judged there and at
// every cycle's end, and trips the bench as a heartbeat loss does.

#include <chrono>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "wavebench/can/can_bus.hpp"
#include "wavebench/canopen/node_guard.hpp"

namespace wavebench::bench {

class NodeGuardWatch {
 public:
  using Clock = canopen::NodeGuard::Clock;

  void clear() noexcept { guards_.clear(); }
  void add(canopen::NodeId node, std::chrono::milliseconds guard_time,
           std::chrono::milliseconds life_time);
  bool guards(canopen::NodeId node) const { return guards_.contains(node); }
  bool empty() const noexcept { return guards_.empty(); }
  // Guarding (re)starts: every request is due now, every life time runs from now.
  void start(Clock::time_point now) noexcept;
  // The bench's loop ran again after a hold that ended at `now` (NodeGuard::excuse).
  void excuse(Clock::time_point now) noexcept {
    for (auto& [node, g] : guards_) g.excuse(now);
  }
  // Sends the requests that are due; a request the bus refuses is retried next time.
  void poll(can::CanBus& bus, Clock::time_point now) noexcept;

  struct Answer {
    canopen::NodeId node;
    canopen::NmtState state;
  };
  // A frame from the bus: an answer of a guarded node (toggle right), if it is one.
  std::optional<Answer> on_frame(const can::Frame& frame, Clock::time_point now) noexcept;

  struct Lost {
    canopen::NodeId node;
    bool toggle;      // the toggle did not alternate (else: no answer within the life time)
    double silent_s;  // wall time since its last answer
    std::chrono::milliseconds guard_time;
    std::chrono::milliseconds life_time;
  };
  std::optional<Lost> lost(Clock::time_point now) const noexcept;
  // The trip reason for `lost` of the device `device`.
  static std::string describe(const Lost& lost, const std::string& device);

  const canopen::NodeGuard* guard(canopen::NodeId node) const;
  std::vector<const canopen::NodeGuard*> all() const;

 private:
  std::map<canopen::NodeId, canopen::NodeGuard> guards_;
};

}  // namespace wavebench::bench
