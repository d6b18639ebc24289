#pragma once
// Keeps the brake controller's watchdog fed and watches the link, on its own thread with its
// own BrakeClient (its own libmodbus context). A link without a valid reply for longer than
// link_loss_timeout raises BrakeEvent::link_lost: the safety event the daemon acts on
// (bench.md §7). Alarm edges in the status word are reported too.

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include "wavebench/modbus/brake_client.hpp"

namespace wavebench::modbus {

struct BrakeEvent {
  enum class Kind { link_lost, link_restored, alarm_raised, alarm_cleared };
  Kind kind;
  std::string reason;
};

std::string to_string(BrakeEvent::Kind kind);

// Receives events on the supervisor's thread; must not block for long nor throw.
class BrakeEventSink {
 public:
  virtual ~BrakeEventSink() = default;
  virtual void on_brake_event(const BrakeEvent& event) noexcept = 0;
};

class BrakeSupervisor {
 public:
  BrakeSupervisor(BrakeClientConfig config, BrakeEventSink& sink);
  ~BrakeSupervisor();
  BrakeSupervisor(const BrakeSupervisor&) = delete;
  BrakeSupervisor& operator=(const BrakeSupervisor&) = delete;

  void start();
  void stop() noexcept;

  // Stops writing heartbeats while the link is still polled (commissioning and tests of the
  // controller's watchdog).
  void suspend_heartbeat(bool suspended) noexcept { heartbeat_suspended_ = suspended; }

  bool link_lost() const noexcept { return link_lost_; }
  std::optional<BrakeReadback> latest() const;
  // When latest() was read (steady clock); the epoch until the first readback.
  BrakeClient::Clock::time_point latest_time() const;
  std::string last_error() const;
  uint64_t heartbeats_sent() const noexcept { return heartbeats_; }
  uint64_t cycles() const noexcept { return cycles_; }

 private:
  void run() noexcept;
  void cycle(BrakeClient& client, bool& watchdog_armed);

  BrakeClientConfig config_;
  BrakeEventSink& sink_;
  std::thread thread_;
  std::mutex mutex_;
  std::condition_variable wake_;
  bool stop_requested_ = false;
  mutable std::mutex data_mutex_;
  std::optional<BrakeReadback> latest_;
  BrakeClient::Clock::time_point latest_time_{};
  std::string last_error_;
  std::atomic<bool> heartbeat_suspended_{false};
  std::atomic<bool> link_lost_{false};
  std::atomic<uint64_t> heartbeats_{0};
  std::atomic<uint64_t> cycles_{0};
  bool alarm_seen_ = false;
};

}  // namespace wavebench::modbus
