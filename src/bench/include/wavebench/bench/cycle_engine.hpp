#pragma once
// The bench's cycle (bench.md §1): on every SYNC of the injected clock a cycle opens; the TPDOs
// of the bench's CANopen devices that follow it are handed to their devices, which write their
// channels into the cycle's record; the cycle closes when every expected frame arrived (the
// simulated clock then sends the next SYNC at once) or when the next SYNC opens a new one. On
// the simulated clock the engine tells the clock which late answers are worth waiting for: those
// of devices that answered since the last wait gave up on them. At
// its end the other devices (the Modbus brake) add their latest values, the sample goes to the
// observers, then to the bench's own check (safety). A channel that did not arrive keeps its
// flag clear and is never filled in.
//
// Runs on the bench thread; never blocks (observers must not either).

#include <chrono>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "wavebench/bench/bench_device.hpp"
#include "wavebench/bench/cycle_clock.hpp"
#include "wavebench/bench/sync_lateness_histogram.hpp"
#include "wavebench/canopen/master.hpp"

namespace wavebench::bench {

class SampleObserver;

class CycleEngine {
 public:
  struct Statistics {
    std::uint64_t syncs_sent = 0;
    std::uint64_t samples = 0;
    std::uint64_t incomplete_samples = 0;
    std::uint64_t late_frames = 0;  // a frame outside its cycle, twice, or malformed
  };
  using CycleCheck = std::function<void(const CycleRecord&)>;

  CycleEngine(canopen::Master& master, CycleClock& clock);
  CycleEngine(const CycleEngine&) = delete;
  CycleEngine& operator=(const CycleEngine&) = delete;

  // The devices of the cycle: CANopen ones by their TPDOs (after their configure()), others at
  // the cycle's end. Subscribes the TPDOs' COB-IDs on the master.
  void attach(std::vector<CanopenDevice*> canopen_devices, std::vector<BenchDevice*> others);
  // Starts SYNC; `check` runs after the observers at each cycle's end.
  void start(CycleCheck check);
  void stop() noexcept;
  bool running() const noexcept { return running_; }

  void add_observer(SampleObserver& observer);
  void remove_observer(SampleObserver& observer);

  const CycleRecord& latest() const noexcept { return latest_; }
  const Statistics& statistics() const noexcept { return stats_; }
  const SyncLatenessHistogram& lateness() const noexcept { return lateness_; }
  // Real clock: the SYNC's lateness behind its deadline, from the clock's tick.
  void add_lateness(double seconds) { lateness_.add(seconds); }
  CycleClock& clock() noexcept { return clock_; }
  // Payload bits per cycle on the bus (SYNC and every TPDO), for the bus-load estimate.
  double bits_per_cycle() const;
  // Simulated clock: the devices whose late answers a SYNC waited for (and got) since start(),
  // by name.
  const std::vector<std::string>& late_devices() const noexcept { return late_devices_; }

 private:
  struct FrameSource {
    CanopenDevice* device;
    std::size_t tpdo;
    std::uint32_t bit;
  };
  void on_sync(std::uint64_t index, std::int64_t time_ns);
  void on_frame(const FrameSource& source, const can::Frame& frame) noexcept;
  void close() noexcept;
  // After the cycle timeout: answers still coming from devices not known to be mute.
  bool awaits_answers() noexcept;
  void note_late(std::uint32_t missing) noexcept;

  canopen::Master& master_;
  CycleClock& clock_;
  std::vector<CanopenDevice*> canopen_;
  std::vector<BenchDevice*> others_;
  std::vector<FrameSource> sources_;
  std::vector<SampleObserver*> observers_;
  CycleCheck check_;
  std::uint32_t expected_ = 0;
  std::uint32_t arrived_ = 0;
  std::uint32_t mute_ = 0;     // sources a wait gave up on, until they send again
  std::uint32_t awaited_ = 0;  // sources the open cycle waits for past its timeout
  std::vector<std::string> late_devices_;
  std::chrono::steady_clock::time_point last_warning_{};
  bool open_ = false;
  bool running_ = false;
  CycleRecord record_;
  CycleRecord latest_;
  Statistics stats_;
  SyncLatenessHistogram lateness_;
};

}  // namespace wavebench::bench
