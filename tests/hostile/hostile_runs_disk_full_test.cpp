// The disk filling up in the middle of a run (issue #8): a dynamic run on the in-process
// simulated bench whose sample-log writes start failing is tripped at the first failure, ends
// `aborted` with the reason in the index and the outcome (even when results.json cannot be
// written), and the bench goes safe: the input stops and stays stopped.
//
// The full disk is RLIMIT_FSIZE (tests/support/file_size_limit.hpp): no root, no mount, and a
// write past it fails as a write to a full disk does (EFBIG instead of ENOSPC).
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <vector>

#include "file_size_limit.hpp"
#include "wavebench/bench/bench_config.hpp"
#include "wavebench/bench/bench_factory.hpp"
#include "wavebench/procedures/run_executor.hpp"
#include "wavebench/storage/run_store.hpp"
#include "wavebench/storage/sample_log.hpp"

namespace wavebench::procedures {
namespace {

namespace fs = std::filesystem;

// Every sample the bench acquires, kept by the test itself (the log cannot show what happened
// after it stopped being written).
class InputTrace final : public bench::SampleObserver {
 public:
  struct Point {
    std::int64_t receive_time_ns;
    double theta_in_rad, input_speed_rad_s;
  };
  void on_sample(const storage::SyncSample& s) noexcept override {
    if (points_.size() < points_.capacity()) {
      points_.push_back({s.receive_time_ns, s.theta_in_rad, s.input_speed_rad_s});
    }
  }
  void reserve(std::size_t n) { points_.reserve(n); }
  const std::vector<Point>& points() const { return points_; }

 private:
  std::vector<Point> points_;
};

TEST(HostileRunsDiskFull, ADynamicRunWhoseLogCannotBeWrittenIsTrippedAndEndsAborted) {
  const fs::path root =
      fs::temp_directory_path() / ("wavebench-hostile-disk-full-" + std::to_string(::getpid()));
  fs::remove_all(root);
  const auto config = bench::default_simulated_bench_config();
  auto bench = bench::make_simulated_bench(config);
  bench->connect();
  InputTrace trace;
  trace.reserve(2'000'000);
  bench->add_observer(trace);
  storage::RunStore store(root, "test");

  RunRequest request;
  request.procedure = "dynamic";  // 100 rpm: 10.5 rad/s at the input for two minutes
  request.options = {{"calibrate_twin", false}};
  request.config_text = config.text;
  request.twin = false;
  request.report = false;
  // About 5 s of samples fit: the log fails during the recording, the input at speed.
  constexpr std::size_t kRecordsThatFit = 5000;
  std::string run_id;
  RunOutcome outcome;
  {
    wavebench::testing::FileSizeLimit disk(storage::sample_log_header_size(0) +
                                           kRecordsThatFit * storage::kSampleLogRecordSize);
    outcome = execute_run(*bench, store, request, [&](const RunProgress& p) {
      if (run_id.empty()) {
        run_id = p.run_id;
        // And results.json cannot be written either: its name is taken by a folder.
        fs::create_directory(store.paths(run_id).results);
      }
    });
  }
  // The bench keeps running its loop for a second of bench time: it must stay still.
  const std::size_t at_return = trace.points().size();
  bench->idle_for(1.0);
  bench->remove_observer(trace);
  const auto state = bench->state();
  bench->disconnect();

  std::printf("outcome: %s (%s)\n", storage::run_status_name(outcome.status),
              outcome.reason.c_str());
  EXPECT_EQ(outcome.status, storage::RunStatus::kAborted);
  EXPECT_EQ(
      outcome.reason.rfind("sample log: file size limit reached (File too large) at sample ", 0),
      0u)
      << outcome.reason;
  EXPECT_EQ(state, bench::BenchLifecycle::kFault);
  EXPECT_TRUE(outcome.results.contains("results_error")) << outcome.results.dump().substr(0, 400);

  const auto record = store.find_run(outcome.run_id);
  ASSERT_TRUE(record);
  EXPECT_EQ(record->status, storage::RunStatus::kAborted);
  EXPECT_EQ(record->reason, outcome.reason);
  std::ifstream status_in(store.paths(outcome.run_id).status);
  const auto status = nlohmann::json::parse(status_in);
  EXPECT_EQ(status["status"], "aborted");
  EXPECT_EQ(status["reason"], outcome.reason);

  // The last record that reached the file, found in the test's own trace.
  const auto log = storage::read_sample_log(store.paths(outcome.run_id).samples);
  ASSERT_GT(log.samples.size(), 1000u);
  EXPECT_LE(log.samples.size(), kRecordsThatFit);
  const auto last_logged = log.samples.back().receive_time_ns;
  const auto& points = trace.points();
  const auto it = std::find_if(points.begin(), points.end(),
                               [&](const auto& p) { return p.receive_time_ns == last_logged; });
  ASSERT_NE(it, points.end());
  const auto failed_at = static_cast<std::size_t>(it - points.begin());
  ASSERT_GT(std::abs(points[failed_at].input_speed_rad_s), 5.0) << "not failing at speed";
  // Up to a flush interval (100 records) until the write fails, then the quick stop.
  constexpr std::size_t kSettle = 100 + 400;
  ASSERT_GT(points.size(), failed_at + kSettle + 500) << "too little trace after the failure";
  double max_speed_after = 0, min_in = INFINITY, max_in = -INFINITY;
  for (std::size_t i = failed_at + kSettle; i < points.size(); ++i) {
    max_speed_after = std::max(max_speed_after, std::abs(points[i].input_speed_rad_s));
    min_in = std::min(min_in, points[i].theta_in_rad);
    max_in = std::max(max_in, points[i].theta_in_rad);
  }
  const double travel = points.back().theta_in_rad - points[failed_at].theta_in_rad;
  std::printf(
      "log failed at sample %zu (at %.1f rad/s); input travel after it %.3f rad; after %zu "
      "samples of settle: |speed| <= %.4f rad/s, theta_in within %.5f rad over %zu samples "
      "(%zu of them after execute_run returned)\n",
      failed_at, points[failed_at].input_speed_rad_s, travel, kSettle, max_speed_after,
      max_in - min_in, points.size() - failed_at - kSettle, points.size() - at_return);
  EXPECT_LT(max_speed_after, 0.1);
  EXPECT_LT(max_in - min_in, 0.01);
  EXPECT_LT(std::abs(travel), 5.0);  // the run went on for 628 rad
  // Far from the two minutes a dynamic run takes: it was stopped, not finished.
  EXPECT_LT(at_return, 30'000u);
  fs::remove_all(root);
}

}  // namespace
}  // namespace wavebench::procedures
