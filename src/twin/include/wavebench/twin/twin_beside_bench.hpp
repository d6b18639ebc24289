#pragma once
// The twin beside the bench (bench.md §5): a SampleObserver that hands every SYNC sample to
// the gear model running on its own thread, driven by the measured input angle and load
// torque (measured_drive_twin.hpp says how and why dynamically).
//
// Usage in a run (runs::execute_run):
//
//   twin::TwinBesideBench twin(bench.description().twin_gear, bench.description().sense);
//   bench.add_observer(twin);
//   ... run the procedure (BenchAborted or not) ...
//   bench.remove_observer(twin);
//   const twin::TwinRunReport& live = twin.finish();          // drains the queue, joins
//   twin::write_twin_csv(run_dir / "twin.csv", live.points);  // twin_overlay.hpp
//   results["twin"] = twin::to_json(live);                    // lag, drops, solver figures
//   results["twin"]["residual"] = procedures::to_json(
//       twin::twin_overlay_residual(twin::twin_overlay(live.points), analyser));
//   // At the end, with every sample of the run (e.g. read back from samples.wbs):
//   auto cal = twin::calibrate_twin(description.twin_gear, description.sense, samples,
//                                   analyser, static_result_or_null);   // twin_calibrator.hpp
//   twin::write_calibrated_twin_config(run_dir / "twin-calibrated.yaml", cal);
//   results["twin"]["calibration"] = twin::to_json(cal);  // residual before/after, floor, ...
//   results["twin"]["calibration"]["config"] = "twin-calibrated.yaml";
//
// on_sample() copies six numbers into a bounded lock-free queue and returns; a full queue
// counts the sample as dropped, it never waits. The constructor throws std::invalid_argument
// when the twin's gear cannot be simulated or its ratio is not the bench's.

#include <atomic>
#include <boost/lockfree/spsc_queue.hpp>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>
#include <vector>

#include "wavebench/bench/bench.hpp"
#include "wavebench/twin/measured_drive_twin.hpp"
#include "wavebench/twin/residual_watch.hpp"

namespace wavebench::twin {

struct TwinBesideBenchOptions {
  // Samples (262 s at 1 kHz, 12 MB): room for the simulated clock outrunning the twin.
  std::size_t queue_capacity = 1u << 18;
  TwinSolverOptions solver;
  // The residual watched per output revolution (residual_watch.hpp), on the twin's thread.
  bool diagnose = true;
  ResidualWatchOptions diagnosis;
  // Called on the twin's thread with each new flag (also logged there, never on the bench's).
  std::function<void(const DiagnosticFlag&)> on_flag;
};

// Lag = bench time of the newest sample received − the bench time the twin has reached,
// measured each time the twin finishes a batch.
struct TwinLag {
  double p50_s = 0, p99_s = 0, max_s = 0;
  std::size_t measurements = 0;
};

struct TwinRunReport {
  // One per sample the twin took, in order; index = arrival number (0, 1, ...), the sample
  // log's index when every sample goes to the log; a dropped sample leaves a gap.
  std::vector<TwinPoint> points;
  std::uint64_t samples_received = 0;
  std::uint64_t samples_dropped = 0;  // queue full
  std::uint64_t samples_predicted = 0;
  TwinLag lag;
  std::int64_t solver_steps = 0;
  double thread_cpu_s = 0;     // CPU time of the twin's thread
  std::string error;           // the model failed on the twin's thread (then it stops predicting)
  DiagnosticReport diagnosis;  // empty when options.diagnose is off
  bool diagnosed = false;
};

class TwinBesideBench final : public bench::SampleObserver {
 public:
  TwinBesideBench(const model::GearParams& twin_gear, const procedures::GearSense& sense,
                  TwinBesideBenchOptions options = {});
  ~TwinBesideBench() override;
  TwinBesideBench(const TwinBesideBench&) = delete;
  TwinBesideBench& operator=(const TwinBesideBench&) = delete;

  void on_sample(const storage::SyncSample& sample) noexcept override;

  // Stops taking samples, lets the twin finish what is queued, joins its thread. Idempotent.
  const TwinRunReport& finish();

  std::uint64_t samples_dropped() const noexcept {
    return dropped_.load(std::memory_order_relaxed);
  }
  std::uint64_t samples_received() const noexcept {
    return received_.load(std::memory_order_relaxed);
  }
  // The flags raised so far (any thread; a lock shared with the twin's thread only).
  std::vector<DiagnosticFlag> diagnostic_flags() const;

 private:
  void run() noexcept;
  void wake() noexcept;

  void watch_residual(double reached_s);

  MeasuredDriveTwin twin_;
  std::unique_ptr<ResidualWatch> watch_;
  std::size_t watched_ = 0;  // points fed to watch_
  bool watch_failed_ = false;
  mutable std::mutex flags_mutex_;
  std::vector<DiagnosticFlag> flags_;
  std::function<void(const DiagnosticFlag&)> on_flag_;
  boost::lockfree::spsc_queue<TwinSampleInput> ring_;  // bench thread -> twin thread
  std::atomic<std::uint64_t> received_{0};
  std::atomic<std::uint64_t> dropped_{0};
  std::atomic<std::int64_t> newest_time_ns_{0};
  std::atomic<bool> stopping_{false};
  std::atomic<bool> sleeping_{false};
  std::atomic<std::uint32_t> signal_{0};
  std::vector<double> lags_s_;
  TwinRunReport report_;
  bool finished_ = false;
  std::thread thread_;
};

nlohmann::json to_json(const TwinLag& lag);
// Counts, lag and solver figures (not the points).
nlohmann::json to_json(const TwinRunReport& report);

}  // namespace wavebench::twin
