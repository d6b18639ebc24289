#pragma once
// The thread that owns the bench (bench.hpp: one bench thread makes every call but the
// thread-safe ones). It builds and connects the bench, runs one run at a time through a
// RunLauncher, keeps a real-clock bench's event loop turning between runs, and answers the
// API threads with snapshots of its state.

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <thread>

#include "wavebench/bench/bench.hpp"
#include "wavebench/daemon/daemon_state.hpp"
#include "wavebench/daemon/live_sample_buffer.hpp"
#include "wavebench/daemon/manual_session.hpp"
#include "wavebench/daemon/post_run_queue.hpp"
#include "wavebench/daemon/run_launcher.hpp"
#include "wavebench/procedures/settled_point.hpp"
#include "wavebench/storage/run_store.hpp"

namespace wavebench::daemon {

// Called on the bench thread. Throws std::invalid_argument for a bad config.
using BenchFactory = std::function<std::unique_ptr<bench::Bench>()>;

// The commissioning check on the bench thread (bench_check.hpp); returns its report as JSON.
// Nothing may move: the bench is inactive while it runs.
using BenchCheck = std::function<nlohmann::json(bench::Bench&)>;

// The real one, bench::check_bench on the daemon's connected bench (src/commissioning_check.cpp,
// built with the executable: the library itself does not link the bench).
BenchCheck make_commissioning_check();

struct CheckOutcome {
  enum class Kind { kDone, kRejected, kUnavailable };
  Kind kind = Kind::kDone;
  nlohmann::json report;
  std::string detail;
};

struct ActiveRun {
  std::string run_id;  // empty until the executor has created the run
  std::string procedure;
  std::string phase;
  double fraction = 0;      // of the recording, by time
  double remaining_s = -1;  // of the recording; negative: not known
  StatedProgress stated;    // what the executor last said, told forward by status()
  // The twin's diagnosis flags so far (results.json twin.diagnosis.flags[] entries).
  nlohmann::json diagnosis_flags = nlohmann::json::array();
  // A static run's settled positions so far (the console's TE-against-output-angle view); the
  // newest kMaxPoints.
  static constexpr std::size_t kMaxPoints = 2000;
  std::deque<procedures::SettledPoint> points;
};

// The newest run started: a new run replaces the previous one's verdict at once.
struct FinishedRun {
  std::string run_id;
  // running (recording), processing (its post-run work queued or going on), complete,
  // aborted, or "failed" when the executor threw
  std::string status;
  std::string reason;
  std::string procedure;
  std::string unit_serial;
  std::string verdict;  // PASS, FAIL, UNDECIDED; empty: none (yet)
};

struct BenchStatus {
  DaemonState state = DaemonState::kIdle;
  bench::BenchLifecycle lifecycle = bench::BenchLifecycle::kUnconfigured;
  std::string fault_reason;
  std::string connect_error;  // why the bench is idle, when connecting failed
  std::optional<bench::BenchDescription> description;
  std::vector<storage::ChannelInfo> extra_channels;  // the bench's, in SyncSample::extra order
  std::vector<bench::BenchDeviceInfo> devices;
  std::optional<ActiveRun> run;
  std::optional<FinishedRun> last_run;
  std::vector<PostRunStatus> post_runs;  // recorded runs whose results are still being made
  std::optional<bench::AcquisitionStats> acquisition;  // refreshed on the bench thread
  ManualState manual;                                  // the manual panel (manual_session.hpp)
};

// What POST /api/runs gets back.
struct StartOutcome {
  enum class Kind {
    kStarted,     // run_id set (empty when the executor had not named it within the wait)
    kBadRequest,  // detail names the option
    kRejected,    // the bench cannot take a run now (busy, fault, not connected)
    kFailed,      // the executor failed before the run started
  };
  Kind kind = Kind::kStarted;
  std::string run_id;
  std::string detail;
};

class BenchThread {
 public:
  // `store` and `launcher` outlive the thread. `config_text` goes into every run request.
  BenchThread(BenchFactory factory, storage::RunStore& store, RunLauncher& launcher,
              std::string config_text, LiveSampleBuffer& live);
  ~BenchThread();
  BenchThread(const BenchThread&) = delete;
  BenchThread& operator=(const BenchThread&) = delete;

  // Starts the thread, builds the bench and tries to connect it; returns when that is done.
  // Rethrows what the factory threw (a bad config); a failed connect leaves the daemon idle
  // with connect_error set.
  void start();
  // From any thread. Queues the run and waits (up to `wait`) until the executor has named it
  // or refused it.
  StartOutcome start_run(procedures::RunRequest request,
                         std::chrono::milliseconds wait = std::chrono::seconds(30));
  // Trips the bench with `reason` when a run is active; returns whether one was.
  bool abort_run(const std::string& reason);
  // The operator's stop (POST /api/stop): trips the bench with `reason` (safe state: drive
  // disabled, brake off) whether or not a run is active; an active run ends aborted with it,
  // its data kept. Unlike a trip by a limit or a device, it is not a fault: once the safe
  // state holds, the bench thread clears it and the bench is inactive again, ready for the
  // next start without a reset. False when no bench is there.
  bool stop(const std::string& reason = kOperatorStopReason);
  static constexpr const char* kOperatorStopReason = "stopped by operator";
  // Clears a fault or retries a failed connect, on the bench thread; returns the error text
  // (empty when the bench is ready afterwards).
  std::string reset(std::chrono::milliseconds wait = std::chrono::seconds(30));
  // Before start(): what check() runs. Without one, check() answers kUnavailable.
  void set_check(BenchCheck check) { check_ = std::move(check); }
  // Runs the commissioning check on the bench thread; refused while a run is active or queued
  // (no run starts while it runs: the bench thread does one job at a time).
  CheckOutcome check(std::chrono::milliseconds wait = std::chrono::seconds(60));
  BenchStatus status() const;
  // Trips the bench with `reason` if a run is active, lets the run finish aborted, puts the
  // bench in its safe state, disconnects and joins; then waits for the post-run work of every
  // recorded run (nothing recorded is left unfinished). Idempotent.
  void shutdown(const std::string& reason);
  // Trips the bench and, unless called on the bench thread itself, waits up to `wait` for the
  // active run to be finished (marked aborted) by the bench thread. For the last resort.
  void emergency_stop(const std::string& reason, std::chrono::milliseconds wait) noexcept;
  // The manual panel: `ask` runs on the session unless a run is active or queued, or the bench
  // is not ready (409 naming why); a run is refused while the panel is engaged.
  std::optional<ManualRefusal> manual(
      const std::function<std::optional<ManualRefusal>(ManualSession&)>& ask);
  // Ends the panel's motion; a go-to in progress is interrupted by tripping the bench.
  void manual_stop(const std::string& why);

 private:
  class StatsObserver;
  struct Job;

  void thread_main();
  void connect_bench();
  void run_job(Job& job);
  void reset_job(Job& job);
  void check_job(Job& job);
  void idle_until_job(std::unique_lock<std::mutex>& lock);
  void trip(const std::string& reason);
  // On the bench thread: an operator stop's trip, once the bench shows it, cleared back to
  // inactive; a fault with any other reason (a real trip came first) stays.
  void settle_operator_stop();
  void refresh_stats_on_bench_thread();
  void post_run_done(const std::string& run_id, const procedures::RunOutcome* outcome,
                     const std::string& error);

  BenchFactory factory_;
  BenchCheck check_;
  storage::RunStore& store_;
  RunLauncher& launcher_;
  std::string config_text_;
  LiveSampleBuffer& live_;
  std::unique_ptr<StatsObserver> stats_observer_;

  mutable std::mutex mutex_;
  std::condition_variable wake_;
  std::condition_variable run_ended_;
  std::deque<std::shared_ptr<Job>> jobs_;
  bool stopping_ = false;
  bool started_ = false;
  bench::Bench* bench_ = nullptr;  // set and cleared under mutex_; used only on the bench thread
  std::optional<bench::BenchDescription> description_;
  std::vector<storage::ChannelInfo> extra_channels_;
  std::vector<bench::BenchDeviceInfo> devices_;
  std::string connect_error_;
  std::optional<ActiveRun> run_;
  bool run_queued_ = false;
  std::optional<FinishedRun> last_run_;
  std::string operator_stop_reason_;  // an operator stop not yet settled
  std::uint64_t operator_stops_ = 0;  // how many were asked for
  std::optional<bench::AcquisitionStats> acquisition_;
  ManualSession manual_{[this] { wake_.notify_all(); }};
  std::thread thread_;
  // Last: destroyed (drained) first, while what its work reports to is still there.
  PostRunQueue post_runs_;
};

}  // namespace wavebench::daemon
