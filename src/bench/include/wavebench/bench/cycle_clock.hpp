#pragma once
// What paces the bench's cycles, injected into the cycle engine (one code path for both):
//
//   RealSyncClock       SYNC on absolute deadlines of the steady clock (canopen::SyncProducer);
//                       bench time is real time since start; a cycle closes when all its PDOs
//                       arrived or at the next SYNC.
//   SimulatedSyncClock  the next SYNC goes out as soon as the cycle's PDOs arrived: bench time
//                       is SYNC index × period, and a run takes a fraction of its real duration.
//                       After a real-time cycle timeout the next SYNC still waits for answers
//                       that are coming (a device slower than the rate: SYNCs must not queue up
//                       in it), up to a bound (the heartbeat timeout of real time) after which
//                       the cycle closes incomplete; a device that did not answer by then is
//                       not waited for again until it answers. Every wait is counted.

#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>

#include "wavebench/can/can_bus.hpp"
#include "wavebench/canopen/master.hpp"
#include "wavebench/canopen/sync_producer.hpp"

namespace wavebench::bench {

class CycleClock {
 public:
  // SYNC `index` goes out now; its cycle starts at `time_ns` of bench time.
  using SyncHandler = std::function<void(std::uint64_t index, std::int64_t time_ns)>;

  virtual ~CycleClock() = default;
  // Bench time from here on starts at 0 (connect()).
  virtual void reset() noexcept = 0;
  virtual void start(SyncHandler on_sync) = 0;
  virtual void stop() noexcept = 0;
  // Bench time [s] since reset().
  virtual double now() const noexcept = 0;
  // Real time [s] since reset().
  double real_elapsed() const noexcept;
  // The open cycle has all its frames.
  virtual void cycle_complete() noexcept = 0;
  // A frame received before the open cycle's SYNC went out belongs to an earlier cycle, however
  // late it is processed (real clock; frames without a receive time are taken).
  virtual bool received_after_sync(const can::Frame& frame) const noexcept {
    (void)frame;
    return true;
  }
  // Whether bench time is paced by the devices rather than by real time.
  virtual bool simulated() const noexcept = 0;
  // Simulated clock, after a cycle's timeout: `awaited()` says whether answers of the open
  // cycle are still coming (the next SYNC waits for them); `given_up()` runs when the bound
  // closed the cycle without them.
  struct LateAnswers {
    std::function<bool()> awaited;
    std::function<void()> given_up;
  };
  virtual void on_late_answers(LateAnswers hooks) { (void)hooks; }

  struct Statistics {
    std::uint64_t late = 0;              // the SYNC producer woke late (real clock)
    std::uint64_t skipped = 0;           // whole periods skipped (real clock)
    std::uint64_t cycles_timed_out = 0;  // a cycle past its real-time timeout (simulated)
    // Simulated: cycles whose next SYNC waited past the timeout for a device's late answers
    // (the device is slower than the configured rate), the longest such wait, and the cycles
    // the bound closed without them.
    std::uint64_t cycles_waited_for_devices = 0;
    double longest_device_wait_s = 0;
    std::uint64_t cycles_given_up = 0;
  };
  virtual Statistics statistics() const noexcept = 0;

 protected:
  std::chrono::steady_clock::time_point t0_ = std::chrono::steady_clock::now();
};

class RealSyncClock final : public CycleClock {
 public:
  using TickHook = std::function<void(const canopen::SyncProducer::Tick&)>;
  RealSyncClock(canopen::Master& master, std::chrono::microseconds period);

  void reset() noexcept override { t0_ = std::chrono::steady_clock::now(); }
  void start(SyncHandler on_sync) override;
  void stop() noexcept override;
  double now() const noexcept override { return real_elapsed(); }
  void cycle_complete() noexcept override {}
  bool received_after_sync(const can::Frame& frame) const noexcept override;
  bool simulated() const noexcept override { return false; }
  Statistics statistics() const noexcept override;
  // Every SYNC's deadline and send time (the jitter benchmark, the lateness histogram).
  void on_tick(TickHook hook) { tick_hook_ = std::move(hook); }

 private:
  canopen::Master& master_;
  std::chrono::microseconds period_;
  TickHook tick_hook_;
  bool running_ = false;
  std::chrono::system_clock::time_point sync_sent_wall_{};
};

class SimulatedSyncClock final : public CycleClock {
 public:
  // `wait_bound`: real time after a SYNC past which late answers are not waited for.
  SimulatedSyncClock(can::CanBus& bus, double period_s, std::chrono::milliseconds cycle_timeout,
                     std::chrono::milliseconds wait_bound = std::chrono::milliseconds(1000));
  ~SimulatedSyncClock() override;

  void reset() noexcept override;
  void start(SyncHandler on_sync) override;
  void stop() noexcept override;
  double now() const noexcept override { return static_cast<double>(index_) * period_s_; }
  void cycle_complete() noexcept override;
  bool simulated() const noexcept override { return true; }
  void on_late_answers(LateAnswers hooks) override { late_ = std::move(hooks); }
  Statistics statistics() const noexcept override { return stats_; }

 private:
  void send_sync() noexcept;
  void arm(std::chrono::steady_clock::duration after) noexcept;
  void on_timer() noexcept;

  can::CanBus& bus_;
  double period_s_;
  std::chrono::milliseconds cycle_timeout_;
  std::chrono::milliseconds wait_bound_;
  LateAnswers late_;
  std::chrono::steady_clock::time_point sync_sent_{};
  bool waiting_ = false;  // past the cycle timeout, for answers that are coming
  Statistics stats_;
  boost::asio::steady_timer timer_;
  SyncHandler on_sync_;
  bool running_ = false;
  std::uint64_t index_ = 0;
  std::uint64_t generation_ = 0;
  std::shared_ptr<bool> alive_ = std::make_shared<bool>(true);
};

}  // namespace wavebench::bench
