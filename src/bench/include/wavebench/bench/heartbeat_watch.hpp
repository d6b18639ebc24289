#pragma once
// The bench's one heartbeat watcher (bench.md §7), judged on the wall (steady) clock whatever
// the bench clock, so that a silent bus is noticed within the consumer time of real time.
//
// On the simulated clock the simulated nodes produce heartbeats in bench time, and a simulated
// bench may run slower than real time (a loaded machine): wall-clock silence alone would trip
// falsely there. A node is lost when it has been silent (no heartbeat) for longer than the
// timeout of wall time AND, on the simulated clock, either also for longer than the timeout of
// bench time, or it has sent no frame at all (PDO, SDO, EMCY) for longer than the timeout of
// wall time. On the real clock bench time is wall time.
//
// A loop that was held (the bench thread did not run it: nothing was read, nothing could react)
// is not silence of the nodes: after loop_resumed() silence is judged from then on; the silence
// reported stays the time since the node's last heartbeat.
//
// Also keeps, per node, the largest wall-clock gap between two processed heartbeats: how long
// the event loop left them unread.

#include <chrono>
#include <cstdint>
#include <map>
#include <optional>
#include <vector>

#include "wavebench/can/frame.hpp"
#include "wavebench/canopen/cob_id.hpp"
#include "wavebench/canopen/nmt.hpp"

namespace wavebench::bench {

class HeartbeatWatch {
 public:
  using Clock = std::chrono::steady_clock;

  // Watches `nodes` from `now_s` (bench) and `wall` with `timeout_s` (0: heartbeats are not
  // judged); `simulated`: bench time is not wall time.
  template <typename Nodes>
  void arm(const Nodes& nodes, double now_s, double timeout_s, bool simulated = false,
           Clock::time_point wall = Clock::now()) {
    last_.clear();
    for (const auto n : nodes) last_[n] = Node{now_s, wall, wall, 0, 0, std::nullopt};
    timeout_s_ = timeout_s;
    simulated_ = simulated;
  }
  void disarm() noexcept { last_.clear(); }
  bool watches(canopen::NodeId node) const { return last_.contains(node); }
  // The event loop runs again after a hold that ended at `wall`.
  void loop_resumed(Clock::time_point wall) noexcept { resumed_ = wall; }

  // A heartbeat of `node` processed at bench time `now_s` and wall time `processed`.
  void seen(canopen::NodeId node, double now_s, Clock::time_point processed,
            std::optional<canopen::NmtState> state = std::nullopt) noexcept;
  // Any frame from the bus: a device's EMCY, TPDO or SDO answer shows its node alive.
  void frame(const can::Frame& frame, Clock::time_point processed) noexcept;

  struct Lost {
    canopen::NodeId node;
    double silent_s;  // wall time since its last heartbeat
  };
  // The first node lost by the rule above, if any.
  std::optional<Lost> lost(double now_s, Clock::time_point wall = Clock::now()) const noexcept;
  bool missing(canopen::NodeId node, double now_s,
               Clock::time_point wall = Clock::now()) const noexcept;
  double timeout() const noexcept { return timeout_s_; }

  std::uint64_t count(canopen::NodeId node) const noexcept;
  double largest_gap(canopen::NodeId node) const noexcept;

  // What the bench panel shows of each watched node: the NMT state of its last heartbeat and
  // the wall time since then.
  struct NodeView {
    canopen::NodeId node;
    std::optional<canopen::NmtState> state;  // none before its first heartbeat
    double age_s;
    std::uint64_t count;
  };
  std::vector<NodeView> nodes(Clock::time_point wall = Clock::now()) const;

 private:
  struct Node {
    double last_s = 0;              // bench time of the last heartbeat
    Clock::time_point processed{};  // wall time of the last heartbeat
    Clock::time_point any_frame{};  // wall time of the last frame of any kind
    std::uint64_t count = 0;
    double largest_gap_s = 0;
    std::optional<canopen::NmtState> state;
  };
  bool silent(const Node& n, double now_s, Clock::time_point wall) const noexcept;

  std::map<canopen::NodeId, Node> last_;
  double timeout_s_ = 0;
  bool simulated_ = false;
  Clock::time_point resumed_{};
};

}  // namespace wavebench::bench
