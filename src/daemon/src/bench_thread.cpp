#include "wavebench/daemon/bench_thread.hpp"

#include <spdlog/spdlog.h>

#include <exception>
#include <future>
#include <stdexcept>

#include "wavebench/daemon/realtime_scheduling.hpp"

namespace wavebench::daemon {

// Keeps the acquisition statistics fresh: they may only be read on the bench thread, which is
// inside the executor during a run, so the sample callback samples them now and then.
class BenchThread::StatsObserver : public bench::SampleObserver {
 public:
  explicit StatsObserver(BenchThread& owner) : owner_(owner) {}
  void on_sample(const storage::SyncSample& /*sample*/) noexcept override {
    if (++count_ % kEvery != 0) return;
    owner_.refresh_stats_on_bench_thread();
  }

 private:
  static constexpr std::uint64_t kEvery = 100;
  BenchThread& owner_;
  std::uint64_t count_ = 0;
};

struct BenchThread::Job {
  enum class Kind { kRun, kReset, kCheck };
  Kind kind = Kind::kRun;
  procedures::RunRequest request;
  std::promise<StartOutcome> started;  // kRun: fulfilled once
  bool started_set = false;
  std::promise<std::string> reset_done;   // kReset: error text
  std::promise<CheckOutcome> check_done;  // kCheck

  void settle(StartOutcome outcome) {
    if (started_set) return;
    started_set = true;
    started.set_value(std::move(outcome));
  }
};

BenchThread::BenchThread(BenchFactory factory, storage::RunStore& store, RunLauncher& launcher,
                         std::string config_text, LiveSampleBuffer& live)
    : factory_(std::move(factory)),
      store_(store),
      launcher_(launcher),
      config_text_(std::move(config_text)),
      live_(live),
      stats_observer_(std::make_unique<StatsObserver>(*this)),
      post_runs_([this](const std::string& id, const procedures::RunOutcome* outcome,
                        const std::string& error) { post_run_done(id, outcome, error); }) {}

BenchThread::~BenchThread() {
  shutdown("daemon shutting down");
}

void BenchThread::start() {
  std::promise<void> built;
  auto built_future = built.get_future();
  {
    std::lock_guard lock(mutex_);
    if (started_) throw std::logic_error("BenchThread::start called twice");
    started_ = true;
  }
  thread_ = std::thread([this, &built] {
    std::unique_ptr<bench::Bench> bench;
    try {
      bench = factory_();
      if (!bench) throw std::runtime_error("the bench factory returned no bench");
    } catch (...) {
      built.set_exception(std::current_exception());
      return;
    }
    {
      std::lock_guard lock(mutex_);
      bench_ = bench.get();
      description_ = bench->description();
      manual_.set_bench(*description_);
      extra_channels_ = bench->extra_channels();
      devices_ = bench->device_info();
    }
    if (!description_->simulated_clock) {
      // SYNC from user space wakes late on an ordinary kernel (bench.md §1): ask for real-time
      // scheduling where permitted; its absence is logged, not fatal.
      const auto rt = request_realtime_scheduling();
      if (rt.fifo && rt.memory_locked) {
        spdlog::info("bench thread: {}", rt.message);
      } else {
        spdlog::warn("bench thread: {}; acquisition runs on ordinary scheduling", rt.message);
      }
    }
    connect_bench();
    built.set_value();
    thread_main();
    bench->disconnect();
    std::lock_guard lock(mutex_);
    bench_ = nullptr;
    // The bench is destroyed when `bench` leaves scope, after the pointer is gone.
  });
  try {
    built_future.get();
  } catch (...) {
    thread_.join();
    std::lock_guard lock(mutex_);
    stopping_ = true;
    throw;
  }
}

void BenchThread::connect_bench() {
  try {
    bench_->connect();
    bench_->add_observer(live_);
    bench_->add_observer(*stats_observer_);
    refresh_stats_on_bench_thread();
    std::lock_guard lock(mutex_);
    connect_error_.clear();
    spdlog::info("bench '{}' connected (unit {}, {} clock)", description_->name,
                 description_->unit_serial, description_->simulated_clock ? "simulated" : "real");
  } catch (const std::exception& e) {
    spdlog::error("bench '{}' did not connect: {}", description_->name, e.what());
    bench_->disconnect();
    std::lock_guard lock(mutex_);
    connect_error_ = e.what();
  }
}

void BenchThread::refresh_stats_on_bench_thread() {
  auto stats = bench_->acquisition_stats();
  std::lock_guard lock(mutex_);
  acquisition_ = stats;
}

void BenchThread::thread_main() {
  std::unique_lock lock(mutex_);
  for (;;) {
    idle_until_job(lock);
    if (jobs_.empty()) return;  // stopping with nothing left to do
    auto job = jobs_.front();
    jobs_.pop_front();
    lock.unlock();
    if (job->kind == Job::Kind::kRun) {
      run_job(*job);
    } else if (job->kind == Job::Kind::kCheck) {
      check_job(*job);
    } else {
      reset_job(*job);
    }
    lock.lock();
  }
}

void BenchThread::idle_until_job(std::unique_lock<std::mutex>& lock) {
  // Between runs the bench's event loop keeps turning (heartbeats, the brake's watchdog,
  // acquisition, the live view) at about real-time pace: on the simulated clock idle_for()
  // returns at once, so the rest of each slice is slept.
  constexpr auto kSlice = std::chrono::milliseconds(50);
  while (jobs_.empty() && !stopping_) {
    const bool pump = bench_ != nullptr && connect_error_.empty() &&
                      bench_->state() != bench::BenchLifecycle::kUnconfigured;
    if (!pump) {
      wake_.wait_for(lock, std::chrono::milliseconds(200));
      continue;
    }
    // Shorter slices while the manual panel is engaged: its dead-man is checked between them.
    const auto slice = manual_.engaged() ? ManualSession::kServeSlice : kSlice;
    const auto start = std::chrono::steady_clock::now();
    lock.unlock();
    try {
      manual_.serve(*bench_);
      bench_->idle_for(std::chrono::duration<double>(slice).count());
      settle_operator_stop();
      refresh_stats_on_bench_thread();
    } catch (const std::exception& e) {
      spdlog::debug("idle: {}", e.what());
    }
    lock.lock();
    const auto spent = std::chrono::steady_clock::now() - start;
    if (spent < slice && jobs_.empty() && !stopping_) wake_.wait_for(lock, slice - spent);
  }
}

void BenchThread::run_job(Job& job) {
  const std::string procedure = job.request.procedure;
  {
    std::lock_guard lock(mutex_);
    run_queued_ = false;
    run_ = ActiveRun{"", procedure, "starting", 0, -1, {}, nlohmann::json::array(), {}};
  }
  auto progress = [this, &job](const procedures::RunProgress& p) {
    {
      std::lock_guard lock(mutex_);
      if (run_) {
        if (run_->run_id.empty() && !p.run_id.empty()) {
          spdlog::info("run {} started ({})", p.run_id, run_->procedure);
          // The previous run's verdict goes: status says this run is the newest.
          last_run_ = FinishedRun{p.run_id,
                                  "running",
                                  "",
                                  run_->procedure,
                                  job.request.unit_serial.empty() && description_
                                      ? description_->unit_serial
                                      : job.request.unit_serial,
                                  ""};
        }
        if (!p.run_id.empty()) run_->run_id = p.run_id;
        run_->phase = p.phase;
        run_->stated.report(p.fraction, p.remaining_s);
      }
    }
    if (!p.run_id.empty()) job.settle({StartOutcome::Kind::kStarted, p.run_id, ""});
  };
  // On the twin's thread: the flag is logged there already; here it joins /api/status.
  job.request.on_diagnosis = [this](const nlohmann::json& flag) {
    std::lock_guard lock(mutex_);
    if (run_) run_->diagnosis_flags.push_back(flag);
  };
  job.request.on_point = [this](const procedures::SettledPoint& point) {
    std::lock_guard lock(mutex_);
    if (!run_) return;
    if (run_->points.size() >= ActiveRun::kMaxPoints) run_->points.pop_front();
    run_->points.push_back(point);
  };
  FinishedRun finished;
  try {
    auto recorded = launcher_.record(*bench_, store_, job.request, progress);
    job.settle({StartOutcome::Kind::kStarted, recorded.run_id, ""});
    spdlog::info("run {} recorded; its post-run work is queued (about {:.0f} s)", recorded.run_id,
                 recorded.post_run_estimate_s);
    finished = {recorded.run_id, "processing", "", recorded.procedure, recorded.unit_serial, ""};
    post_runs_.push(std::move(recorded));
  } catch (const std::invalid_argument& e) {
    spdlog::warn("run request refused: {}", e.what());
    job.settle({StartOutcome::Kind::kBadRequest, "", e.what()});
    std::lock_guard lock(mutex_);
    run_.reset();
    run_ended_.notify_all();
    return;
  } catch (const std::exception& e) {
    std::string id;
    {
      std::lock_guard lock(mutex_);
      if (run_) id = run_->run_id;
    }
    spdlog::error("run {} failed: {}", id.empty() ? procedure : id, e.what());
    job.settle({StartOutcome::Kind::kFailed, id, e.what()});
    finished = {id, "failed", e.what(), procedure, job.request.unit_serial, ""};
  }
  try {
    refresh_stats_on_bench_thread();
  } catch (const std::exception&) {
  }
  std::lock_guard lock(mutex_);
  run_.reset();
  // A run of a stand-in launcher may have finished already (its post-run work is nothing).
  if (!last_run_ || last_run_->run_id != finished.run_id || last_run_->status == "running") {
    last_run_ = finished;
  }
  run_ended_.notify_all();
}

void BenchThread::post_run_done(const std::string& run_id, const procedures::RunOutcome* outcome,
                                const std::string& error) {
  if (outcome) {
    if (outcome->status == storage::RunStatus::kComplete) {
      spdlog::info("run {} complete", run_id);
    } else {
      spdlog::warn("run {} {}: {}", run_id, storage::run_status_name(outcome->status),
                   outcome->reason);
    }
    if (const auto w = outcome->results.find("warnings"); w != outcome->results.end()) {
      for (const auto& warning : *w)
        spdlog::warn("run {}: {}", run_id,
                     (warning.is_string() ? warning.get<std::string>() : warning.dump()));
    }
  }
  std::lock_guard lock(mutex_);
  // Only the newest run's end is the last run: an older run finishing in the background does
  // not bring its verdict back over a newer run.
  if (!last_run_ || last_run_->run_id != run_id) return;
  if (outcome) {
    last_run_->status = storage::run_status_name(outcome->status);
    last_run_->reason = outcome->reason;
    const auto v = outcome->results.find("verdict");
    last_run_->verdict = v != outcome->results.end() && v->is_string() ? v->get<std::string>() : "";
  } else {
    last_run_->status = "failed";
    last_run_->reason = "post-run work failed: " + error;
  }
}

void BenchThread::reset_job(Job& job) {
  std::string error;
  try {
    bool connected = false;
    {
      std::lock_guard lock(mutex_);
      connected = connect_error_.empty();
    }
    if (!connected) {
      connect_bench();
      std::lock_guard lock(mutex_);
      error = connect_error_;
    } else if (bench_->state() == bench::BenchLifecycle::kFault) {
      const auto reason = bench_->fault_reason();
      bench_->clear_fault();
      spdlog::info("fault cleared ({})", reason);
    }
  } catch (const std::exception& e) {
    error = e.what();
    spdlog::warn("fault not cleared: {}", error);
  }
  job.reset_done.set_value(error);
}

void BenchThread::check_job(Job& job) {
  CheckOutcome outcome;
  try {
    outcome.report = check_(*bench_);
    refresh_stats_on_bench_thread();
  } catch (const std::exception& e) {
    outcome.kind = CheckOutcome::Kind::kUnavailable;
    outcome.detail = e.what();
  }
  job.check_done.set_value(std::move(outcome));
}

CheckOutcome BenchThread::check(std::chrono::milliseconds wait) {
  auto job = std::make_shared<Job>();
  job->kind = Job::Kind::kCheck;
  auto done = job->check_done.get_future();
  {
    std::lock_guard lock(mutex_);
    if (stopping_ || !bench_) return {CheckOutcome::Kind::kRejected, {}, "the daemon is stopping"};
    if (run_ || run_queued_) {
      return {CheckOutcome::Kind::kRejected,
              {},
              "a run is active" +
                  (run_ && !run_->run_id.empty() ? " (" + run_->run_id + ")" : std::string()) +
                  ": the check runs with the bench inactive"};
    }
    if (!check_) return {CheckOutcome::Kind::kUnavailable, {}, "no commissioning check here"};
    if (manual_.engaged())
      return {
          CheckOutcome::Kind::kRejected, {}, "the manual panel has the servo on; switch it off"};
    jobs_.push_back(job);
  }
  wake_.notify_all();
  if (done.wait_for(wait) != std::future_status::ready)
    return {CheckOutcome::Kind::kUnavailable, {}, "the check did not finish in time"};
  return done.get();
}

StartOutcome BenchThread::start_run(procedures::RunRequest request, std::chrono::milliseconds wait) {
  auto job = std::make_shared<Job>();
  job->kind = Job::Kind::kRun;
  job->request = std::move(request);
  job->request.config_text = config_text_;
  auto started = job->started.get_future();
  std::optional<bench::BenchDescription> description;
  std::size_t extra_channels = 0;
  {
    std::lock_guard lock(mutex_);
    description = description_;
    extra_channels = extra_channels_.size();
  }
  // Malformed before busy: a bad request is answered as such whatever the bench is doing.
  if (description) {
    try {
      launcher_.check(job->request, *description, extra_channels, store_.root());
    } catch (const std::invalid_argument& e) {
      return {StartOutcome::Kind::kBadRequest, "", e.what()};
    }
  }
  {
    std::lock_guard lock(mutex_);
    if (stopping_ || !bench_) return {StartOutcome::Kind::kRejected, "", "the daemon is stopping"};
    if (!connect_error_.empty()) {
      return {StartOutcome::Kind::kRejected, "",
              "the bench is not connected (" + connect_error_ + "); retry with a reset"};
    }
    if (run_ || run_queued_) {
      const std::string id = run_ ? run_->run_id : std::string();
      return {StartOutcome::Kind::kRejected, id,
              "a run is already active" + (id.empty() ? std::string() : " (" + id + ")")};
    }
    if (bench_->state() == bench::BenchLifecycle::kFault) {
      const auto fault = bench_->fault_reason();
      if (!operator_stop_reason_.empty() && fault.ends_with(operator_stop_reason_)) {
        return {StartOutcome::Kind::kRejected, "",
                "the bench is stopping (operator stop) and ready again in a moment; retry"};
      }
      return {StartOutcome::Kind::kRejected, "",
              "the bench is in fault (" + fault + "); clear it with a reset"};
    }
    if (manual_.engaged()) {
      return {StartOutcome::Kind::kRejected, "",
              "the manual panel has the servo on: switch it off before a run"};
    }
    run_queued_ = true;
    jobs_.push_back(job);
  }
  wake_.notify_all();
  if (started.wait_for(wait) != std::future_status::ready) {
    return {StartOutcome::Kind::kStarted, "", "the run was queued but has not named itself yet"};
  }
  return started.get();
}

bool BenchThread::abort_run(const std::string& reason) {
  {
    std::lock_guard lock(mutex_);
    if (!run_ && !run_queued_) return false;
  }
  trip(reason);
  return true;
}

bool BenchThread::stop(const std::string& reason) {
  {
    std::lock_guard lock(mutex_);
    if (!bench_) return false;
    // Before the trip: the bench thread must know the fault it will see is this one.
    operator_stop_reason_ = reason;
    ++operator_stops_;
  }
  // The manual panel lets go too, before the trip: once the fault is settled the bench is
  // inactive, and nothing the panel wanted before the stop may power it again.
  manual_.servo(false);  // the jog, the go-to and the brake go with the servo
  manual_.stop(reason);
  trip(reason);
  return true;
}

void BenchThread::settle_operator_stop() {
  std::string reason;
  std::uint64_t stops = 0;
  {
    std::lock_guard lock(mutex_);
    if (operator_stop_reason_.empty() || !bench_) return;
    reason = operator_stop_reason_;
    stops = operator_stops_;
  }
  // The trip is posted to the bench's event loop: until it has run, there is nothing to settle.
  if (bench_->state() != bench::BenchLifecycle::kFault) return;
  const auto fault = bench_->fault_reason();
  // The bench keeps the first trip's reason (a bench may prefix it, "operator stop: ..."); any
  // text after ours is a problem found while stopping (e.g. a drive that ignored the quick stop).
  if (!fault.ends_with(reason)) {
    spdlog::warn("operator stop: the bench is in fault for another reason ({}); reset needed",
                 fault);
  } else {
    try {
      bench_->clear_fault();  // checks that no cause persists (heartbeats, brake link)
      spdlog::info("operator stop: safe state reached, bench inactive and ready");
    } catch (const std::exception& e) {
      spdlog::warn("operator stop: the bench stays in fault: {}", e.what());
    }
  }
  // Only now: until the fault is cleared, status() shows "stopping", not a fault. A stop that
  // came meanwhile (Esc pressed twice) is settled on the next pass.
  std::lock_guard lock(mutex_);
  if (operator_stops_ == stops) operator_stop_reason_.clear();
}

void BenchThread::trip(const std::string& reason) {
  std::lock_guard lock(mutex_);
  if (!bench_) return;
  spdlog::warn("safe state requested: {}", reason);
  bench_->request_stop(reason);  // thread-safe and non-blocking by contract
}

std::string BenchThread::reset(std::chrono::milliseconds wait) {
  auto job = std::make_shared<Job>();
  job->kind = Job::Kind::kReset;
  auto done = job->reset_done.get_future();
  {
    std::lock_guard lock(mutex_);
    if (stopping_ || !bench_) return "the daemon is stopping";
    if (run_ || run_queued_) return "a run is active; abort it first";
    jobs_.push_back(job);
  }
  wake_.notify_all();
  if (done.wait_for(wait) != std::future_status::ready) return "the reset did not finish in time";
  return done.get();
}

BenchStatus BenchThread::status() const {
  std::lock_guard lock(mutex_);
  BenchStatus s;
  s.description = description_;
  s.extra_channels = extra_channels_;
  s.devices = devices_;
  s.connect_error = connect_error_;
  s.run = run_;
  if (s.run) {
    const auto now = s.run->stated.at();
    s.run->fraction = now.fraction;
    s.run->remaining_s = now.remaining_s;
  }
  s.last_run = last_run_;
  s.post_runs = post_runs_.status();
  s.acquisition = acquisition_;
  s.manual = manual_.state();
  if (bench_ && connect_error_.empty()) {
    s.lifecycle = bench_->state();
    if (s.lifecycle == bench::BenchLifecycle::kFault) s.fault_reason = bench_->fault_reason();
  }
  s.state = daemon_state_of(s.lifecycle, run_.has_value() || run_queued_);
  // An operator stop on its way back to inactive is not shown as a fault.
  if (s.state == DaemonState::kFault && !operator_stop_reason_.empty() &&
      s.fault_reason.ends_with(operator_stop_reason_)) {
    s.state = DaemonState::kStopping;
    s.fault_reason.clear();
  }
  return s;
}

void BenchThread::emergency_stop(const std::string& reason,
                                 std::chrono::milliseconds wait) noexcept {
  try {
    std::unique_lock lock(mutex_);
    if (!bench_) return;
    bench_->request_stop(reason);
    if (std::this_thread::get_id() == thread_.get_id()) return;
    run_ended_.wait_for(lock, wait, [&] { return !run_.has_value(); });
  } catch (...) {
  }
}

std::optional<ManualRefusal> BenchThread::manual(
    const std::function<std::optional<ManualRefusal>(ManualSession&)>& ask) {
  std::lock_guard lock(mutex_);
  if (stopping_ || !bench_) return ManualRefusal{409, "the daemon is stopping"};
  if (!connect_error_.empty())
    return ManualRefusal{409, "the bench is not connected (" + connect_error_ + ")"};
  if (run_ || run_queued_)
    return ManualRefusal{409, "a run is active: the manual panel waits until it has ended"};
  if (bench_->state() == bench::BenchLifecycle::kFault)
    return ManualRefusal{
        409, "the bench is in fault (" + bench_->fault_reason() + "); clear it with a reset"};
  return ask(manual_);
}

void BenchThread::manual_stop(const std::string& why) {
  if (manual_.stop(why)) trip(why);
}

void BenchThread::shutdown(const std::string& reason) {
  {
    std::lock_guard lock(mutex_);
    if (stopping_ && !thread_.joinable()) return;
    stopping_ = true;
    // Queued runs never start; the active one is tripped below.
    for (auto& job : jobs_) {
      if (job->kind == Job::Kind::kRun) {
        job->settle({StartOutcome::Kind::kRejected, "", "the daemon is stopping"});
      } else if (job->kind == Job::Kind::kCheck) {
        job->check_done.set_value({CheckOutcome::Kind::kRejected, {}, "the daemon is stopping"});
      } else {
        job->reset_done.set_value("the daemon is stopping");
      }
    }
    jobs_.clear();
    run_queued_ = false;
    if (run_ && bench_) {
      spdlog::warn("stopping with run {} active: {}", run_->run_id, reason);
      bench_->request_stop(reason);
    }
  }
  wake_.notify_all();
  if (thread_.joinable()) thread_.join();
  // The bench is safe and disconnected; what was recorded is finished before the daemon ends.
  if (const auto pending = post_runs_.status(); !pending.empty()) {
    spdlog::info("waiting for the post-run work of {} recorded run(s) (about {:.0f} s)",
                 pending.size(), pending.back().remaining_s);
  }
  post_runs_.drain();
}

}  // namespace wavebench::daemon
