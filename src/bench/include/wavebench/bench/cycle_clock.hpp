#pragma once
// What paces the bench's cycles, injected into the cycle engine (one code path for both):
//
//   RealSyncClock       SYNC on absolute deadlines of the steady clock (canopen::SyncProducer);
//                       bench time is real time since start; a cycle closes when all its PDOs
//                       arrived or at the next SYNC.
//   SimulatedSyncClock  the next SYNC goes out as soon as the cycle's PDOs arrived (or after a
//                       real-time timeout, the missing ones counted): bench time is
//                       SYNC index × period, and a run takes a fraction of its real duration.

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

  struct Statistics {
    std::uint64_t late = 0;              // the SYNC producer woke late (real clock)
    std::uint64_t skipped = 0;           // whole periods skipped (real clock)
    std::uint64_t cycles_timed_out = 0;  // a cycle closed by its real-time timeout (simulated)
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
  SimulatedSyncClock(can::CanBus& bus, double period_s, std::chrono::milliseconds cycle_timeout);
  ~SimulatedSyncClock() override;

  void reset() noexcept override;
  void start(SyncHandler on_sync) override;
  void stop() noexcept override;
  double now() const noexcept override { return static_cast<double>(index_) * period_s_; }
  void cycle_complete() noexcept override { send_sync(); }
  bool simulated() const noexcept override { return true; }
  Statistics statistics() const noexcept override { return {0, 0, timed_out_}; }

 private:
  void send_sync() noexcept;

  can::CanBus& bus_;
  double period_s_;
  std::chrono::milliseconds cycle_timeout_;
  boost::asio::steady_timer timer_;
  SyncHandler on_sync_;
  bool running_ = false;
  std::uint64_t index_ = 0;
  std::uint64_t generation_ = 0;
  std::uint64_t timed_out_ = 0;
  std::shared_ptr<bool> alive_ = std::make_shared<bool>(true);
};

}  // namespace wavebench::bench
