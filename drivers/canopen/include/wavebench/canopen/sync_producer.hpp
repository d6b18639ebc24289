#pragma once
// SYNC producer (CiA 301 §7.2.5) on absolute deadlines t0 + k·period, so late wakeups never
// accumulate into drift. A wakeup that misses whole periods skips them (counted) instead of
// bursting SYNCs onto the bus. With a counter overflow value (0x1019, 2..240) each SYNC carries
// the counter 1..overflow.

#include <boost/asio/steady_timer.hpp>
#include <chrono>
#include <cstdint>
#include <functional>

#include "wavebench/can/can_bus.hpp"

namespace wavebench::canopen {

can::Frame sync_frame(std::uint8_t counter = 0);  // counter 0: no data byte

class SyncProducer {
 public:
  using Clock = std::chrono::steady_clock;
  struct Tick {
    std::uint64_t index;   // k: the SYNC's deadline is t0 + k·period
    std::uint8_t counter;  // the counter sent (0 when none)
    Clock::time_point deadline;
    Clock::time_point sent;  // when it left for the bus
    bool ok;                 // the send succeeded
  };
  struct Statistics {
    std::uint64_t sent = 0;
    std::uint64_t late = 0;     // woke later than the late threshold
    std::uint64_t skipped = 0;  // whole periods missed
    std::uint64_t send_errors = 0;
    Clock::duration max_lateness{};
  };

  SyncProducer(can::CanBus& bus, std::chrono::microseconds period,
               std::uint8_t counter_overflow = 0);
  ~SyncProducer();
  SyncProducer(const SyncProducer&) = delete;
  SyncProducer& operator=(const SyncProducer&) = delete;

  void start();
  void stop() noexcept;
  bool running() const noexcept { return running_; }

  // Called after every SYNC (noexcept hooks: they run on the io_context).
  void on_tick(std::function<void(const Tick&)> hook) { on_tick_ = std::move(hook); }
  // Called when a wakeup is later than `threshold` (default: half a period).
  void on_late(std::function<void(const Tick&, Clock::duration lateness)> hook,
               Clock::duration threshold) {
    on_late_ = std::move(hook);
    late_threshold_ = threshold;
  }
  const Statistics& statistics() const noexcept { return stats_; }
  std::chrono::microseconds period() const noexcept { return period_; }

 private:
  void schedule() noexcept;
  void fire() noexcept;

  can::CanBus& bus_;
  std::chrono::microseconds period_;
  std::uint8_t overflow_;
  std::uint8_t counter_ = 0;
  boost::asio::steady_timer timer_;
  bool running_ = false;
  Clock::time_point t0_{};
  std::uint64_t k_ = 0;
  Clock::duration late_threshold_;
  Statistics stats_;
  std::function<void(const Tick&)> on_tick_;
  std::function<void(const Tick&, Clock::duration)> on_late_;
};

}  // namespace wavebench::canopen
