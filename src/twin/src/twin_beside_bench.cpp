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

double percentile(std::vector<double> sorted, double q) {
  if (sorted.empty()) return 0;
  std::sort(sorted.begin(), sorted.end());
  const auto i = static_cast<std::size_t>(std::ceil(q * static_cast<double>(sorted.size()))) - 1;
  return sorted[std::min(i, sorted.size() - 1)];
}

}  // namespace

TwinBesideBench::TwinBesideBench(const model::GearParams& twin_gear,
                                 const procedures::GearSense& sense, TwinBesideBenchOptions options)
    : twin_(twin_gear, sense, options.solver),
      on_flag_(std::move(options.on_flag)),
      ring_(options.queue_capacity) {
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
      watch_residual(reached);
      if (std::isfinite(reached)) {
        const double newest =
            static_cast<double>(newest_time_ns_.load(std::memory_order_relaxed)) * 1e-9;
        lags_s_.push_back(std::max(0.0, newest - reached));
      }
    } catch (const std::exception& e) {
      report_.error = e.what();
      failed = true;
    }
  }
  if (!failed) {
    try {
      twin_.flush();
      watch_residual(std::numeric_limits<double>::infinity());
    } catch (const std::exception& e) {
      report_.error = e.what();
    }
  }
  report_.thread_cpu_s = thread_cpu_seconds();
}

void TwinBesideBench::watch_residual(double reached_s) {
  if (!watch_ || watch_failed_ || std::isnan(reached_s)) return;
  const auto& points = twin_.points();
  try {
    while (watched_ < points.size() && points[watched_].t_s <= reached_s) {
      watch_->feed(points[watched_]);
      ++watched_;
    }
  } catch (const std::exception& e) {
    // The diagnosis stops; the twin's prediction goes on.
    watch_failed_ = true;
    spdlog::warn("twin diagnosis stopped: {}", e.what());
  }
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
  report_.lag.measurements = lags_s_.size();
  report_.lag.p50_s = percentile(lags_s_, 0.50);
  report_.lag.p99_s = percentile(lags_s_, 0.99);
  report_.lag.max_s = lags_s_.empty() ? 0 : *std::max_element(lags_s_.begin(), lags_s_.end());
  report_.points = twin_.take_points();
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
  if (r.diagnosed) j["diagnosis"] = to_json(r.diagnosis);
  return j;
}

}  // namespace wavebench::twin
