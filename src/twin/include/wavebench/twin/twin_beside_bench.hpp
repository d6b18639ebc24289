#pragma once
// The twin beside the bench (bench.md §5): a SampleObserver that hands every SYNC sample to
// the gear model running on its own thread, driven by the measured input angle and load
// torque (measured_drive_twin.hpp says how and why dynamically).
//
// Usage in a run (procedures::execute_run):
//
//   twin::TwinBesideBenchOptions options;
//   options.overlay_csv = run_dir / "twin.csv";  // written as the twin goes
//   twin::TwinBesideBench twin(bench.description().twin_gear, bench.description().sense,
//                              options);
//   bench.add_observer(twin);
//   ... run the procedure (BenchAborted or not) ...
//   bench.remove_observer(twin);
//   const twin::TwinRunReport& live = twin.finish();  // drains the queue, joins, commits
//   results["twin"] = twin::to_json(live);  // lag, drops, solver figures, residual, floor
//   // At the end, with every sample of the run (e.g. read back from samples.wbs):
//   auto cal = twin::calibrate_twin(description.twin_gear, description.sense, samples,
//                                   analyser, static_result_or_null);   // twin_calibrator.hpp
//   twin::write_calibrated_twin_config(run_dir / "twin-calibrated.yaml", cal);
//   results["twin"]["calibration"] = twin::to_json(cal);  // residual before/after, floor, ...
//   results["twin"]["calibration"]["config"] = "twin-calibrated.yaml";
//
// The twin keeps no point once it is predicted (issue #12): each goes to the diagnosis, the
// residual's running figures, twin.csv and on_point, and is let go.
//
// on_sample() copies six numbers into a bounded lock-free queue and returns; a full queue
// counts the sample as dropped, it never waits. The constructor throws std::invalid_argument
// when the twin's gear cannot be simulated or its ratio is not the bench's.

#include <array>
#include <atomic>
#include <boost/lockfree/spsc_queue.hpp>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "wavebench/bench/bench.hpp"
#include "wavebench/twin/measured_drive_twin.hpp"
#include "wavebench/twin/residual_watch.hpp"
#include "wavebench/twin/twin_overlay.hpp"

namespace wavebench::twin {

struct TwinBesideBenchOptions {
  // Samples (33 s at 1 kHz, 1.5 MB): a twin needing ~20 µs a sample has room for a stall of
  // half a minute on the real clock; the simulated clock waits for it (lockstep_backlog). A
  // larger ring only grows the resident memory of a long run as its pages come into use.
  std::size_t queue_capacity = 1u << 15;
  // Simulated clock only (0 on the real clock): on_sample() waits while more than this many
  // samples are queued, so the bench's clock never runs ahead of the twin (issue #12: the twin
  // keeps up by construction, and a run does not wait for it at its end). The wait costs no
  // bench time there. On the real clock the twin needs ~20 µs a sample against 1 ms.
  std::size_t lockstep_backlog = 0;
  TwinSolverOptions solver;
  // The residual watched per output revolution (residual_watch.hpp), on the twin's thread.
  bool diagnose = true;
  ResidualWatchOptions diagnosis;
  // Called on the twin's thread with each new flag (also logged there, never on the bench's).
  std::function<void(const DiagnosticFlag&)> on_flag;
  // twin.csv (twin_overlay.hpp), written on the twin's thread as points settle and committed
  // by finish(); empty: none.
  std::filesystem::path overlay_csv;
  // Called on the twin's thread with every point once it changes no more, in order.
  std::function<void(const TwinPoint&)> on_point;
};

// Lag = bench time of the newest sample received − the bench time the twin has reached,
// measured each time the twin finishes a batch.
struct TwinLag {
  double p50_s = 0, p99_s = 0, max_s = 0;
  std::size_t measurements = 0;
};

// Lags in log-spaced bins (the percentiles are the bins' upper edges, never above the max).
class LagHistogram {
 public:
  void add(double lag_s);
  double percentile(double q) const;
  double max() const { return max_; }
  std::size_t count() const { return count_; }

 private:
  static constexpr double kFirst = 1e-6;
  static constexpr double kPerDecade = 20;
  std::array<std::uint64_t, 200> bins_{};  // 1 µs .. 10^4 s
  std::size_t count_ = 0;
  double max_ = 0;
};

struct TwinRunReport {
  // Points (one per sample the twin took, index = arrival number, the sample log's index when
  // every sample goes to the log; a dropped sample leaves a gap) and what they add up to.
  std::uint64_t points = 0;
  std::optional<metrology::TwinResidual> residual;  // with at least 8 overlapping points
  double noise_floor_arcsec = 0;                     // TwinOverlaySum::noise_floor_arcsec
  std::uint64_t overlay_rows = 0;                    // written to overlay_csv
  std::string overlay_error;  // twin.csv could not be written (the twin went on)
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
  TwinBesideBench(const model::GearParams& twin_gear, const metrology::GearSense& sense,
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

  void take_settled();
  void take_point(const TwinPoint& point);

  MeasuredDriveTwin twin_;
  std::unique_ptr<ResidualWatch> watch_;
  bool watch_failed_ = false;
  std::vector<TwinPoint> settled_;  // reused: the points of one batch
  TwinOverlaySum overlay_;
  std::unique_ptr<TwinCsvWriter> csv_;
  mutable std::mutex flags_mutex_;
  std::vector<DiagnosticFlag> flags_;
  std::function<void(const DiagnosticFlag&)> on_flag_;
  std::function<void(const TwinPoint&)> on_point_;
  boost::lockfree::spsc_queue<TwinSampleInput> ring_;  // bench thread -> twin thread
  std::atomic<std::uint64_t> received_{0};
  std::atomic<std::uint64_t> dropped_{0};
  std::atomic<std::int64_t> newest_time_ns_{0};
  std::atomic<bool> stopping_{false};
  std::size_t queue_capacity_ = 0;
  std::size_t lockstep_backlog_ = 0;
  std::atomic<bool> sleeping_{false};
  std::atomic<std::uint32_t> signal_{0};
  LagHistogram lags_;
  TwinRunReport report_;
  bool finished_ = false;
  std::thread thread_;
};

nlohmann::json to_json(const TwinLag& lag);
// Counts, lag and solver figures (not the points).
nlohmann::json to_json(const TwinRunReport& report);

}  // namespace wavebench::twin
