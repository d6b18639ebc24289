#include "wavebench/twin/twin_beside_bench.hpp"

#include <spdlog/spdlog.h>
#include <time.h>

#include <algorithm>
#include <cmath>
#include <exception>
#include <limits>

namespace wavebench::twin {
namespace {

double thread_cpu_seconds() {
  timespec ts{};
  if (clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts) != 0) return 0;
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

}  // namespace

// 20 bins per decade from 1 µs: a percentile within 12 %, in constant memory however long
// the run.
void LagHistogram::add(double lag_s) {
  ++count_;
  max_ = std::max(max_, lag_s);
  const double decades = lag_s > kFirst ? std::log10(lag_s / kFirst) : 0.0;
  const auto bin =
      std::min<std::size_t>(static_cast<std::size_t>(decades * kPerDecade), bins_.size() - 1);
  ++bins_[bin];
}

double LagHistogram::percentile(double q) const {
  if (count_ == 0) return 0;
  const auto rank = static_cast<std::uint64_t>(std::ceil(q * static_cast<double>(count_)));
  std::uint64_t seen = 0;
  for (std::size_t i = 0; i < bins_.size(); ++i) {
    seen += bins_[i];
    if (seen >= rank) {
      return std::min(max_, kFirst * std::pow(10.0, static_cast<double>(i + 1) / kPerDecade));
    }
  }
  return max_;
}

TwinBesideBench::TwinBesideBench(const model::GearParams& twin_gear,
                                 const metrology::GearSense& sense, TwinBesideBenchOptions options)
    : twin_(twin_gear, sense, options.solver),
      on_flag_(std::move(options.on_flag)),
      on_point_(std::move(options.on_point)),
      ring_(options.queue_capacity),
      queue_capacity_(options.queue_capacity),
      lockstep_backlog_(options.lockstep_backlog) {
  // Created here, on the caller's thread: a folder that refuses the file is the caller's
  // error to report, before the twin starts.
  if (!options.overlay_csv.empty()) csv_ = std::make_unique<TwinCsvWriter>(options.overlay_csv);
  if (options.diagnose) {
    watch_ = std::make_unique<ResidualWatch>(twin_gear, sense.ratio, options.diagnosis);
    watch_->on_flag([this](const DiagnosticFlag& flag) {
      spdlog::warn("twin diagnosis: {}", describe(flag));
      {
        std::lock_guard lock(flags_mutex_);
        flags_.push_back(flag);
      }
      if (on_flag_) on_flag_(flag);
    });
  }
  thread_ = std::thread([this] { run(); });
}

TwinBesideBench::~TwinBesideBench() {
  finish();
}

void TwinBesideBench::on_sample(const storage::SyncSample& sample) noexcept {
  // The sample's own index is the log's (assigned on append, 0 before): number them here, in
  // arrival order, which is the log's order too.
  const std::uint64_t sequence = received_.fetch_add(1, std::memory_order_relaxed);
  newest_time_ns_.store(sample.receive_time_ns, std::memory_order_relaxed);
  TwinSampleInput input = twin_input(sample);
  input.index = sequence;
  // The twin's thread drains whatever it finds, failed or not, until finish(): this wait
  // always ends.
  // (write_available() is the producer's side of the queue.)
  while (lockstep_backlog_ > 0 && queue_capacity_ - ring_.write_available() > lockstep_backlog_ &&
         !stopping_.load(std::memory_order_relaxed)) {
    if (sleeping_.load(std::memory_order_seq_cst)) wake();
    std::this_thread::yield();
  }
  if (stopping_.load(std::memory_order_relaxed) || !ring_.push(input)) {
    dropped_.fetch_add(1, std::memory_order_relaxed);
    return;
  }
  // Pairs with the fence in run(): either the twin sees this sample or we see it sleeping.
  std::atomic_thread_fence(std::memory_order_seq_cst);
  if (sleeping_.load(std::memory_order_seq_cst)) wake();
}

void TwinBesideBench::wake() noexcept {
  signal_.fetch_add(1, std::memory_order_seq_cst);
  signal_.notify_one();
}

void TwinBesideBench::run() noexcept {
  std::vector<TwinSampleInput> batch(256);
  bool failed = false;
  for (;;) {
    const std::size_t n = ring_.pop(batch.data(), batch.size());
    if (n == 0) {
      if (stopping_.load(std::memory_order_seq_cst) && ring_.read_available() == 0) break;
      // Sleep until the producer signals; the re-check after raising the flag closes the race
      // with a push that saw the flag still down.
      const std::uint32_t seen = signal_.load(std::memory_order_seq_cst);
      sleeping_.store(true, std::memory_order_seq_cst);
      std::atomic_thread_fence(std::memory_order_seq_cst);
      if (ring_.read_available() == 0 && !stopping_.load(std::memory_order_seq_cst)) {
        signal_.wait(seen);
      }
      sleeping_.store(false, std::memory_order_seq_cst);
      continue;
    }
    if (failed) continue;  // keep draining so that the bench side never fills up
    try {
      for (std::size_t i = 0; i < n; ++i) twin_.push(batch[i]);
      const double reached = twin_.twin_time_s();
      take_settled();
      if (std::isfinite(reached)) {
        const double newest =
            static_cast<double>(newest_time_ns_.load(std::memory_order_relaxed)) * 1e-9;
        lags_.add(std::max(0.0, newest - reached));
      }
    } catch (const std::exception& e) {
      report_.error = e.what();
      failed = true;
    }
  }
  if (!failed) {
    try {
      twin_.flush();
      take_settled();
    } catch (const std::exception& e) {
      report_.error = e.what();
    }
  }
  report_.thread_cpu_s = thread_cpu_seconds();
}

void TwinBesideBench::take_settled() {
  settled_.clear();
  twin_.take_settled_points(settled_);
  for (const auto& p : settled_) take_point(p);
}

void TwinBesideBench::take_point(const TwinPoint& p) {
  ++report_.points;
  overlay_.add(p);
  if (watch_ && !watch_failed_) {
    try {
      watch_->feed(p);
    } catch (const std::exception& e) {
      // The diagnosis stops; the twin's prediction goes on.
      watch_failed_ = true;
      spdlog::warn("twin diagnosis stopped: {}", e.what());
    }
  }
  if (csv_) {
    try {
      csv_->add(p);
    } catch (const std::exception& e) {
      // A full disk ends twin.csv (its temp file is removed); the prediction goes on.
      report_.overlay_error = std::string("twin.csv not written: ") + e.what();
      csv_.reset();
    }
  }
  if (on_point_) on_point_(p);
}

std::vector<DiagnosticFlag> TwinBesideBench::diagnostic_flags() const {
  std::lock_guard lock(flags_mutex_);
  return flags_;
}

const TwinRunReport& TwinBesideBench::finish() {
  if (finished_) return report_;
  finished_ = true;
  stopping_.store(true, std::memory_order_seq_cst);
  wake();
  if (thread_.joinable()) thread_.join();
  report_.samples_received = received_.load();
  report_.samples_dropped = dropped_.load();
  report_.samples_predicted = twin_.predicted();
  report_.solver_steps = twin_.solver_steps();
  report_.lag.measurements = lags_.count();
  report_.lag.p50_s = lags_.percentile(0.50);
  report_.lag.p99_s = lags_.percentile(0.99);
  report_.lag.max_s = lags_.max();
  // Points the twin never got to (it failed): their measurement still belongs in twin.csv.
  for (const auto& p : twin_.take_points()) take_point(p);
  if (overlay_.overlapping() >= 8) report_.residual = overlay_.residual();
  report_.noise_floor_arcsec = overlay_.noise_floor_arcsec();
  if (csv_) {
    try {
      report_.overlay_rows = csv_->rows();
      csv_->commit();
    } catch (const std::exception& e) {
      report_.overlay_rows = 0;
      report_.overlay_error = std::string("twin.csv not written: ") + e.what();
    }
    csv_.reset();
  }
  if (watch_) {
    report_.diagnosis = watch_->report();
    report_.diagnosed = true;
  }
  return report_;
}

nlohmann::json to_json(const TwinLag& lag) {
  return {{"p50_s", lag.p50_s},
          {"p99_s", lag.p99_s},
          {"max_s", lag.max_s},
          {"measurements", lag.measurements}};
}

nlohmann::json to_json(const TwinRunReport& r) {
  nlohmann::json j = {
      {"samples_received", r.samples_received},   {"samples_dropped", r.samples_dropped},
      {"samples_predicted", r.samples_predicted}, {"lag", to_json(r.lag)},
      {"solver_steps", r.solver_steps},           {"thread_cpu_s", r.thread_cpu_s}};
  if (!r.error.empty()) j["error"] = r.error;
  j["points"] = r.points;
  if (r.residual) {
    j["residual"] = metrology::to_json(*r.residual);
    j["residual"]["noise_floor_arcsec"] = r.noise_floor_arcsec;
    if (r.noise_floor_arcsec > 0) {
      j["residual"]["rms_over_noise_floor"] = r.residual->rms_arcsec / r.noise_floor_arcsec;
    }
  }
  if (!r.overlay_error.empty()) j["overlay_error"] = r.overlay_error;
  if (r.diagnosed) j["diagnosis"] = to_json(r.diagnosis);
  return j;
}

}  // namespace wavebench::twin
