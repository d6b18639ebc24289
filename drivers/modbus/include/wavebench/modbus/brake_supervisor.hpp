#pragma once
// Keeps the brake controller's watchdog fed and watches the link, on its own thread. On a bench
// it shares the bench's BrakeClient, so that the line has one master and one libmodbus context
// (issue #9); its heartbeats and polls are routine turns on that link. A link without a valid reply
// for longer than link_loss_timeout raises BrakeEvent::link_lost: the safety event the daemon acts
// on (bench.md §7). Alarm edges in the status word are reported too.

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include "wavebench/modbus/brake_client.hpp"
#include "wavebench/realtime/priority_inheriting_mutex.hpp"

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
  // Supervises through `client`, which must outlive the supervisor.
  BrakeSupervisor(BrakeClient& client, BrakeEventSink& sink);
  // With a BrakeClient of its own (a link of its own): for tools and tests of the supervisor.
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
  void cycle(bool& watchdog_armed);

  std::unique_ptr<BrakeClient> own_client_;
  BrakeClient& client_;
  BrakeClientConfig config_;
  BrakeEventSink& sink_;
  std::thread thread_;
  std::mutex mutex_;
  std::condition_variable wake_;
  bool stop_requested_ = false;
  // Read by the acquisition thread every cycle: priority inheriting.
  mutable realtime::PriorityInheritingMutex data_mutex_;
  std::optional<BrakeReadback> latest_;
  BrakeClient::Clock::time_point latest_time_{};
  std::string last_error_;
  std::atomic<bool> heartbeat_suspended_{false};
  std::atomic<bool> link_lost_{false};
  std::atomic<uint64_t> heartbeats_{0};
  std::atomic<uint64_t> cycles_{0};
  bool alarm_seen_ = false;
  bool armed_now_ = false;  // the last cycle armed the watchdog (supervisor thread only)
};

}  // namespace wavebench::modbus
