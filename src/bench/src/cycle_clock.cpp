#include "wavebench/bench/cycle_clock.hpp"

#include <algorithm>

#include "wavebench/canopen/sync_producer.hpp"

namespace wavebench::bench {

double CycleClock::real_elapsed() const noexcept {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0_).count();
}

// --- real ---------------------------------------------------------------------------------

RealSyncClock::RealSyncClock(canopen::Master& master, std::chrono::microseconds period)
    : master_(master), period_(period) {}

void RealSyncClock::start(SyncHandler on_sync) {
  running_ = true;
  auto& producer = master_.start_sync(period_);
  producer.on_tick([this, on_sync = std::move(on_sync)](const canopen::SyncProducer::Tick& tick) {
    if (!running_) return;
    if (tick_hook_) tick_hook_(tick);
    // The SYNC's send time on the clock of receive timestamps.
    sync_sent_wall_ = std::chrono::system_clock::now() -
                      std::chrono::duration_cast<std::chrono::system_clock::duration>(
                          std::chrono::steady_clock::now() - tick.sent);
    on_sync(tick.index,
            std::chrono::duration_cast<std::chrono::nanoseconds>(tick.sent - t0_).count());
  });
}

void RealSyncClock::stop() noexcept {
  running_ = false;
  master_.stop_sync();
}

bool RealSyncClock::received_after_sync(const can::Frame& frame) const noexcept {
  return frame.timestamp.time_since_epoch().count() == 0 || frame.timestamp >= sync_sent_wall_;
}

CycleClock::Statistics RealSyncClock::statistics() const noexcept {
  Statistics s;
  if (const auto* producer = master_.sync()) {
    s.late = producer->statistics().late;
    s.skipped = producer->statistics().skipped;
  }
  return s;
}

// --- simulated ----------------------------------------------------------------------------

SimulatedSyncClock::SimulatedSyncClock(can::CanBus& bus, double period_s,
                                       std::chrono::milliseconds cycle_timeout,
                                       std::chrono::milliseconds wait_bound)
    : bus_(bus),
      period_s_(period_s),
      cycle_timeout_(cycle_timeout),
      wait_bound_(std::max(wait_bound, cycle_timeout)),
      timer_(bus.context()) {}

SimulatedSyncClock::~SimulatedSyncClock() {
  *alive_ = false;
  stop();
}

void SimulatedSyncClock::reset() noexcept {
  t0_ = std::chrono::steady_clock::now();
  index_ = 0;
  stats_ = {};
}

void SimulatedSyncClock::start(SyncHandler on_sync) {
  on_sync_ = std::move(on_sync);
  running_ = true;
  send_sync();
}

void SimulatedSyncClock::stop() noexcept {
  running_ = false;
  waiting_ = false;
  ++generation_;
  timer_.cancel();
}

void SimulatedSyncClock::cycle_complete() noexcept {
  if (waiting_) {
    // The late answers arrived: the device is slower than the configured rate.
    ++stats_.cycles_waited_for_devices;
    stats_.longest_device_wait_s = std::max(
        stats_.longest_device_wait_s,
        std::chrono::duration<double>(std::chrono::steady_clock::now() - sync_sent_).count());
  }
  send_sync();
}

void SimulatedSyncClock::send_sync() noexcept {
  if (!running_) return;
  waiting_ = false;
  const auto next = index_ + 1;
  // The handler closes the open cycle first, at its own bench time.
  on_sync_(next, std::llround(static_cast<double>(next) * period_s_ * 1e9));
  index_ = next;
  std::error_code ec;
  bus_.send(canopen::sync_frame(), ec);
  sync_sent_ = std::chrono::steady_clock::now();
  arm(cycle_timeout_);
}

void SimulatedSyncClock::arm(std::chrono::steady_clock::duration after) noexcept {
  const auto generation = ++generation_;
  timer_.expires_after(after);
  timer_.async_wait([this, generation, alive = alive_](const boost::system::error_code& e) {
    if (e || !*alive || generation != generation_ || !running_) return;
    on_timer();
  });
}

void SimulatedSyncClock::on_timer() noexcept {
  if (!waiting_) {
    ++stats_.cycles_timed_out;
    // Answers that are coming hold the next SYNC back: queued SYNCs would only lag a slow
    // device further behind (its replies seconds late, until an SDO times out).
    if (late_.awaited && late_.awaited()) {
      waiting_ = true;
      arm(sync_sent_ + wait_bound_ - std::chrono::steady_clock::now());
      return;
    }
  } else {
    ++stats_.cycles_given_up;
    if (late_.given_up) late_.given_up();
  }
  send_sync();
}

}  // namespace wavebench::bench
