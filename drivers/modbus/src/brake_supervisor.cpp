#include "wavebench/modbus/brake_supervisor.hpp"

namespace wavebench::modbus {

std::string to_string(BrakeEvent::Kind kind) {
  switch (kind) {
    case BrakeEvent::Kind::link_lost:
      return "link lost";
    case BrakeEvent::Kind::link_restored:
      return "link restored";
    case BrakeEvent::Kind::alarm_raised:
      return "alarm raised";
    case BrakeEvent::Kind::alarm_cleared:
      return "alarm cleared";
  }
  return "?";
}

BrakeSupervisor::BrakeSupervisor(BrakeClient& client, BrakeEventSink& sink)
    : client_(client), config_(client.config()), sink_(sink) {}

BrakeSupervisor::BrakeSupervisor(BrakeClientConfig config, BrakeEventSink& sink)
    : own_client_(std::make_unique<BrakeClient>(config)),
      client_(*own_client_),
      config_(std::move(config)),
      sink_(sink) {}

BrakeSupervisor::~BrakeSupervisor() {
  stop();
}

void BrakeSupervisor::start() {
  if (thread_.joinable()) return;
  {
    std::lock_guard lock(mutex_);
    stop_requested_ = false;
  }
  thread_ = std::thread([this] { run(); });
}

void BrakeSupervisor::stop() noexcept {
  {
    std::lock_guard lock(mutex_);
    stop_requested_ = true;
  }
  wake_.notify_all();
  if (thread_.joinable()) thread_.join();
}

std::optional<BrakeReadback> BrakeSupervisor::latest() const {
  std::lock_guard lock(data_mutex_);
  return latest_;
}

BrakeClient::Clock::time_point BrakeSupervisor::latest_time() const {
  std::lock_guard lock(data_mutex_);
  return latest_time_;
}

std::string BrakeSupervisor::last_error() const {
  std::lock_guard lock(data_mutex_);
  return last_error_;
}

void BrakeSupervisor::cycle(bool& watchdog_armed) {
  BrakeClient& client = client_;
  armed_now_ = false;
  if (!watchdog_armed) {
    client.set_watchdog(config_.heartbeat.watchdog_timeout);
    watchdog_armed = true;
    armed_now_ = true;
  }
  if (!heartbeat_suspended_) {
    client.heartbeat();
    ++heartbeats_;
  }
  const BrakeReadback r = client.read();
  {
    std::lock_guard lock(data_mutex_);
    latest_ = r;
    latest_time_ = BrakeClient::Clock::now();
  }
  if (r.status.alarm && !alarm_seen_) {
    alarm_seen_ = true;
    sink_.on_brake_event({BrakeEvent::Kind::alarm_raised, r.alarm_text});
  } else if (!r.status.alarm && alarm_seen_) {
    alarm_seen_ = false;
    sink_.on_brake_event({BrakeEvent::Kind::alarm_cleared, "alarm cleared"});
  }
}

void BrakeSupervisor::run() noexcept {
  BrakeClient& client = client_;
  bool watchdog_armed = false;
  uint64_t armed_on_connection = 0;
  auto next = BrakeClient::Clock::now();
  for (;;) {
    {
      std::unique_lock lock(mutex_);
      if (wake_.wait_until(lock, next, [this] { return stop_requested_; })) return;
    }
    next += config_.heartbeat.period;
    const auto now = BrakeClient::Clock::now();
    if (next < now) next = now;  // after a long stall, do not fire a burst of catch-up cycles
    try {
      // A new connection (whichever thread opened it) may be a restarted controller: arm its
      // watchdog again.
      if (!client.connected() || client.connections() != armed_on_connection) {
        watchdog_armed = false;
      }
      cycle(watchdog_armed);
      if (armed_now_) armed_on_connection = client.connections();
      if (link_lost_.exchange(false)) {
        sink_.on_brake_event(
            {BrakeEvent::Kind::link_restored,
             "brake controller at " + to_string(config_.link.endpoint) + " answers again"});
      }
    } catch (const std::exception& e) {
      {
        std::lock_guard lock(data_mutex_);
        last_error_ = e.what();
      }
      const auto silent = BrakeClient::Clock::now() - client.last_success();
      if (silent > config_.link.link_loss_timeout && !link_lost_.exchange(true)) {
        sink_.on_brake_event(
            {BrakeEvent::Kind::link_lost,
             "no valid reply from the brake controller at " + to_string(config_.link.endpoint) +
                 " for " +
                 std::to_string(
                     std::chrono::duration_cast<std::chrono::milliseconds>(silent).count()) +
                 " ms (limit " + std::to_string(config_.link.link_loss_timeout.count()) +
                 " ms): " + e.what()});
      }
    }
    ++cycles_;
  }
}

}  // namespace wavebench::modbus
