#pragma once
// The bench's one heartbeat watcher (bench.md §7): the last heartbeat of every node in bench
// time, judged once per cycle against the consumer time, on either clock (on the simulated
// clock the simulated nodes produce heartbeats in bench time). Also keeps, per node, the largest
// real-time gap between two processed heartbeats: how long the event loop left them unread.

#include <chrono>
#include <cstdint>
#include <map>
#include <optional>
#include <vector>

#include "wavebench/canopen/cob_id.hpp"
#include "wavebench/canopen/nmt.hpp"

namespace wavebench::bench {

class HeartbeatWatch {
 public:
  using Clock = std::chrono::steady_clock;

  // Watches `nodes` from `now_s` with `timeout_s` (0: heartbeats are not judged).
  template <typename Nodes>
  void arm(const Nodes& nodes, double now_s, double timeout_s) {
    last_.clear();
    for (const auto n : nodes) last_[n] = Node{now_s, {}, 0, 0, std::nullopt};
    timeout_s_ = timeout_s;
  }
  void disarm() noexcept { last_.clear(); }
  bool watches(canopen::NodeId node) const { return last_.contains(node); }

  void seen(canopen::NodeId node, double now_s, Clock::time_point processed,
            std::optional<canopen::NmtState> state = std::nullopt) noexcept;

  struct Lost {
    canopen::NodeId node;
    double silent_s;  // bench time since its last heartbeat
  };
  // The first node silent for longer than the timeout, if any.
  std::optional<Lost> lost(double now_s) const noexcept;
  bool missing(canopen::NodeId node, double now_s) const noexcept;
  double timeout() const noexcept { return timeout_s_; }

  std::uint64_t count(canopen::NodeId node) const noexcept;
  double largest_gap(canopen::NodeId node) const noexcept;

  // What the bench panel shows of each watched node: the NMT state of its last heartbeat and
  // the bench time since then.
  struct NodeView {
    canopen::NodeId node;
    std::optional<canopen::NmtState> state;  // none before its first heartbeat
    double age_s;
    std::uint64_t count;
  };
  std::vector<NodeView> nodes(double now_s) const;

 private:
  struct Node {
    double last_s = 0;
    Clock::time_point processed{};
    std::uint64_t count = 0;
    double largest_gap_s = 0;
    std::optional<canopen::NmtState> state;
  };
  std::map<canopen::NodeId, Node> last_;
  double timeout_s_ = 0;
};

}  // namespace wavebench::bench
