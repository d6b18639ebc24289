// Issue #9: runs in a row on the real clock through the daemon's bench thread and the real run
// executor, on the in-process simulated bench. Post-run work (twin calibration, report) used to
// hold the bench's event loop, and the drive's heartbeats waiting unread were then judged lost
// ("heartbeat of node 1 (servo drive) lost") right after each run. Here every run completes and
// the bench stays ready without a reset; the largest gap between two heartbeats of the drive as
// the bench thread processed them is printed (not asserted: wall-clock timing on a shared
// machine).
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <thread>

#include "test_dir.hpp"
#include "wavebench/bench/bench_config.hpp"
#include "wavebench/bench/bench_factory.hpp"
#include "wavebench/daemon/bench_thread.hpp"
#include "wavebench/daemon/live_sample_buffer.hpp"
#include "wavebench/daemon/run_launcher.hpp"
#include "wavebench/storage/run_store.hpp"

namespace wavebench::daemon::testing {
namespace {

// Three runs: enough for the state between runs to carry over twice (a false trip after the
// first would refuse the second); each takes a few seconds of real time on the real clock.
constexpr int kRuns = 3;

runs::RunRequest short_static_run() {
  runs::RunRequest r;
  r.procedure = "static";
  r.options = {{"positions", 4}, {"loads_nm", {0}}};  // one load: half the run time
  r.twin = true;
  r.report = true;
  return r;
}

std::optional<FinishedRun> wait_for_end(const BenchThread& thread, const std::string& id) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::minutes(5);
  while (std::chrono::steady_clock::now() < deadline) {
    const auto s = thread.status();
    if (!s.run && s.last_run && s.last_run->run_id == id) return s.last_run;
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  return std::nullopt;
}

TEST(DaemonOnTheRealClock, StaticRunsInARowNeitherTripNorNeedAReset) {
  const auto dir = fresh_test_dir();
  auto config = bench::default_simulated_bench_config();
  config.description.simulated_clock = false;
  storage::RunStore store(dir / "runs", "test");
  auto launcher = make_executor_run_launcher();
  LiveSampleBuffer live;
  BenchThread thread([config] { return bench::make_bench(config); }, store, *launcher,
                     "sim on the real clock", live);
  thread.start();
  ASSERT_EQ(thread.status().lifecycle, bench::BenchLifecycle::kReady)
      << thread.status().connect_error;

  std::uint64_t heartbeats_before = 0;
  for (int i = 0; i < kRuns; ++i) {
    const auto started = thread.start_run(short_static_run());
    ASSERT_EQ(started.kind, StartOutcome::Kind::kStarted) << "run " << i << ": " << started.detail;
    ASSERT_FALSE(started.run_id.empty());
    const auto finished = wait_for_end(thread, started.run_id);
    ASSERT_TRUE(finished) << "run " << i << " did not end";
    EXPECT_EQ(finished->status, "complete") << "run " << i << ": " << finished->reason;

    // The post-run work was done (twin calibration, report) while the loop kept turning.
    nlohmann::json results;
    std::ifstream(store.paths(started.run_id).dir / "results.json") >> results;
    EXPECT_TRUE(results["twin"].contains("calibration")) << results["twin"].dump();
    EXPECT_TRUE(results.contains("report")) << results.value("report_error", std::string());

    // Idle a little: a trip judged on heartbeats held during the post-run work would show now.
    std::this_thread::sleep_for(std::chrono::milliseconds(700));
    const auto s = thread.status();
    ASSERT_EQ(s.lifecycle, bench::BenchLifecycle::kReady)
        << "after run " << i << ": " << s.fault_reason;
    ASSERT_TRUE(s.acquisition);
    EXPECT_GT(s.acquisition->drive_heartbeats, heartbeats_before) << "after run " << i;
    heartbeats_before = s.acquisition->drive_heartbeats;
  }
  const auto s = thread.status();
  std::printf(
      "%d static runs (4 positions, no load, twin and report) on the real clock: %llu heartbeats "
      "of "
      "the drive processed, largest gap between two %.1f ms (producer period %.0f ms, "
      "consumer time %.0f ms)\n",
      kRuns, static_cast<unsigned long long>(s.acquisition->drive_heartbeats),
      s.acquisition->drive_heartbeat_gap_max_s * 1e3, config.can.heartbeat_producer_s * 1e3,
      config.description.limits.heartbeat_timeout_s * 1e3);
  thread.shutdown("test done");
}

}  // namespace
}  // namespace wavebench::daemon::testing
