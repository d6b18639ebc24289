// Issue #9: runs in a row on the real clock through the daemon's bench thread and the real run
// executor, on the in-process simulated bench. Post-run work (twin calibration, report) used to
// hold the bench's event loop, and the drive's heartbeats waiting unread were then judged lost
// ("heartbeat of node 1 (servo drive) lost") right after each run. Here every run completes and
// the bench stays ready without a reset; the largest gap between two heartbeats of the drive as
// the bench thread processed them is printed (not asserted: wall-clock timing on a shared
// machine). And an idle daemon holds the bench inactive while /api/live streams.
// Each run starts once the one before has recorded, as an operator may (issue #21): its post-run
// work goes on in the background beside the next recording and the idle bench between them, so
// a loop held by it would trip a recording or the idle bench.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <thread>
#include <vector>

#include "test_dir.hpp"
#include "wavebench/bench/bench_config.hpp"
#include "wavebench/bench/bench_factory.hpp"
#include "wavebench/daemon/bench_thread.hpp"
#include "wavebench/daemon/daemon.hpp"
#include "wavebench/daemon/daemon_client.hpp"
#include "wavebench/daemon/live_sample_buffer.hpp"
#include "wavebench/daemon/run_launcher.hpp"
#include "wavebench/simdevices/brake_server.hpp"
#include "wavebench/storage/run_store.hpp"
#include "wavebench/storage/sync_sample.hpp"

namespace wavebench::daemon::testing {
namespace {

// Ten runs (issue #9's acceptance); each takes about ten seconds of real time on the real clock.
constexpr int kRuns = 10;

procedures::RunRequest short_static_run() {
  procedures::RunRequest r;
  r.procedure = "static";
  // One load (half the run time), moves at 250 rad/s (the default 62.8 makes a run last 36 s on
  // the real clock: twice one output turn of travel) and a shorter averaging window.
  r.options = {{"positions", 4}, {"loads_nm", {0}}, {"move_speed_rad_s", 250}, {"window_s", 0.2}};
  r.twin = true;
  r.report = true;
  return r;
}

// The run's recording ended (its post-run work may still be queued or going on).
std::optional<FinishedRun> wait_for_recorded(const BenchThread& thread, const std::string& id) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::minutes(5);
  while (std::chrono::steady_clock::now() < deadline) {
    const auto s = thread.status();
    if (!s.run && s.last_run && s.last_run->run_id == id && s.last_run->status != "running") {
      return s.last_run;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  return std::nullopt;
}

// Every run's post-run work done (issue #21: it runs in the background).
bool wait_for_post_runs(const BenchThread& thread) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::minutes(10);
  while (std::chrono::steady_clock::now() < deadline) {
    const auto s = thread.status();
    if (!s.run && s.post_runs.empty() && s.last_run && s.last_run->status != "processing") {
      return true;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  return false;
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
  ASSERT_EQ(thread.status().lifecycle, bench::BenchLifecycle::kInactive)
      << thread.status().connect_error;

  std::uint64_t heartbeats_before = 0;
  // Idle a little: a trip judged on heartbeats held during the post-run work would show now.
  const auto idle_and_check = [&](const std::string& when) {
    std::this_thread::sleep_for(std::chrono::milliseconds(700));
    const auto s = thread.status();
    ASSERT_EQ(s.lifecycle, bench::BenchLifecycle::kInactive) << when << ": " << s.fault_reason;
    ASSERT_TRUE(s.acquisition);
    EXPECT_GT(s.acquisition->drive_heartbeats, heartbeats_before) << when;
    heartbeats_before = s.acquisition->drive_heartbeats;
  };
  std::vector<std::string> ids;
  const auto t0 = std::chrono::steady_clock::now();
  for (int i = 0; i < kRuns; ++i) {
    const auto started = thread.start_run(short_static_run());
    ASSERT_EQ(started.kind, StartOutcome::Kind::kStarted) << "run " << i << ": " << started.detail;
    ASSERT_FALSE(started.run_id.empty());
    ids.push_back(started.run_id);
    const auto recorded = wait_for_recorded(thread, started.run_id);
    ASSERT_TRUE(recorded) << "run " << i << " did not end";
    EXPECT_TRUE(recorded->status == "processing" || recorded->status == "complete")
        << "run " << i << ": " << recorded->status << ": " << recorded->reason;
    ASSERT_NO_FATAL_FAILURE(idle_and_check("after run " + std::to_string(i)));
  }
  ASSERT_TRUE(wait_for_post_runs(thread)) << "the post-run work did not end";
  ASSERT_NO_FATAL_FAILURE(idle_and_check("after the last post-run work"));

  for (int i = 0; i < kRuns; ++i) {
    const auto record = store.find_run(ids[static_cast<std::size_t>(i)]);
    ASSERT_TRUE(record) << "run " << i;
    EXPECT_EQ(record->status, storage::RunStatus::kComplete)
        << "run " << i << ": " << record->reason;
    // The post-run work was done (twin calibration, report) while the loop kept turning.
    nlohmann::json results;
    std::ifstream(store.paths(ids[static_cast<std::size_t>(i)]).dir / "results.json") >> results;
    EXPECT_EQ(results.value("status", std::string()), "complete") << "run " << i;
    EXPECT_TRUE(results["twin"].contains("calibration"))
        << "run " << i << ": " << results["twin"].dump();
    EXPECT_TRUE(results.contains("report"))
        << "run " << i << ": " << results.value("report_error", std::string());
  }
  const auto s = thread.status();
  std::printf(
      "%d static runs (4 positions, no load, twin and report) on the real clock in %.0f s: %llu "
      "heartbeats of the drive processed, largest gap between two %.1f ms (producer period %.0f "
      "ms, consumer time %.0f ms)\n",
      kRuns, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(),
      static_cast<unsigned long long>(s.acquisition->drive_heartbeats),
      s.acquisition->drive_heartbeat_gap_max_s * 1e3, config.can.heartbeat_producer_s * 1e3,
      config.description.limits.heartbeat_timeout_s * 1e3);
  thread.shutdown("test done");
}

// Issue #9: the daemon waits inactive. Connected and with no run, the drive's statusword (as the
// daemon reports it) says switch on disabled or ready to switch on, the brake output is off (as
// read back, and the simulated controller's enable bit), and /api/live streams samples with
// both angles and the torque.
TEST(DaemonOnTheRealClock, IdleDaemonHoldsTheBenchInactiveAndStreamsLiveSamples) {
  const auto dir = fresh_test_dir();
  auto config = bench::default_simulated_bench_config();
  config.description.simulated_clock = false;
  bench::SimulatedBenchAccess* access = nullptr;  // set on the bench thread before start() returns
  DaemonSetup setup;
  setup.bench_factory = [config, &access] {
    auto bench = bench::make_bench(config);
    access = bench::simulated_access(*bench);
    return bench;
  };
  setup.launcher = make_executor_run_launcher();
  setup.runs_dir = dir / "runs";
  setup.port = 0;
  setup.token = "0123456789abcdef0123456789abcdef";
  setup.config_text = config.text;
  Daemon daemon(std::move(setup));
  daemon.start();
  ASSERT_NE(access, nullptr);
  DaemonClient client("http://127.0.0.1:" + std::to_string(daemon.port()),
                      "0123456789abcdef0123456789abcdef");

  // The acquisition figures are refreshed while the bench idles: wait until every readback the
  // checks below read has come once (the brake's, the drive's statusword, a heartbeat of each
  // node). On a loaded machine the first of them may take seconds; what they say is judged after.
  const auto settled = [](const nlohmann::json& s) {
    const auto& a = s["acquisition"];
    if (!a.is_object() || a["brake_output_on"].is_null() || !a["drive_statusword"].is_number() ||
        !a["nodes"].is_array() || a["nodes"].size() < 3U)
      return false;
    for (const auto& node : a["nodes"])
      if (!node["heartbeat_age_s"].is_number()) return false;
    return true;
  };
  nlohmann::json status;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(30);
  do {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    status = client.get("/api/status").body;
  } while (std::chrono::steady_clock::now() < deadline && !settled(status));
  EXPECT_EQ(status["lifecycle"], "inactive") << status.dump();
  // Its devices with their state and command interfaces, in configuration order.
  const auto& devices = status["devices"];
  ASSERT_EQ(devices.size(), 4U) << status.dump();
  EXPECT_EQ(devices[0]["name"], "servo drive");
  EXPECT_EQ(devices[0]["node"], 1);
  EXPECT_EQ(devices[0]["channels"][0]["name"], "theta_in");
  EXPECT_EQ(devices[0]["commands"][1]["name"], "input_velocity");
  EXPECT_EQ(devices[0]["commands"][1]["unit"], "rad/s");
  EXPECT_EQ(devices[1]["name"], "output encoder");
  EXPECT_EQ(devices[1]["channels"][0]["name"], "theta_out");
  EXPECT_EQ(devices[2]["channels"][0]["name"], "torque");
  EXPECT_EQ(devices[3]["name"], "brake controller");
  EXPECT_TRUE(devices[3]["node"].is_null());
  EXPECT_EQ(devices[3]["channels"][1]["name"], "brake_torque");
  EXPECT_TRUE(status["run"].is_null());
  const auto& acquisition = status["acquisition"];
  ASSERT_TRUE(acquisition["drive_statusword"].is_number()) << status.dump();
  const auto statusword = acquisition["drive_statusword"].get<unsigned>();
  EXPECT_TRUE((statusword & 0x4F) == 0x40 || (statusword & 0x6F) == 0x21)
      << "statusword " << statusword << ": " << acquisition["drive_state"];
  const auto state = acquisition["drive_state"].get<std::string>();
  EXPECT_TRUE(state == "switch on disabled" || state == "ready to switch on") << state;
  EXPECT_EQ(acquisition["brake_output_on"], false) << status.dump();
  // The bench panel's readbacks: the brake's coil temperature and status word, no alarm, and
  // every CANopen node operational with a recent heartbeat.
  EXPECT_TRUE(acquisition["brake_coil_temperature_c"].is_number()) << status.dump();
  EXPECT_TRUE(acquisition["brake_status_word"].is_number()) << status.dump();
  EXPECT_TRUE(acquisition["brake_alarm"].is_null()) << status.dump();
  ASSERT_EQ(acquisition["nodes"].size(), 3U) << status.dump();
  for (const auto& node : acquisition["nodes"]) {
    EXPECT_EQ(node["nmt_state"], "operational") << node.dump();
    ASSERT_TRUE(node["heartbeat_age_s"].is_number()) << node.dump();
    // Producer 100 ms; the bound is the trip's own (a busier machine than that would have
    // tripped the bench, which the lifecycle above already rules out), not a timing promise.
    EXPECT_LT(node["heartbeat_age_s"].get<double>(), 5.0) << node.dump();
    EXPECT_GT(node["heartbeats"].get<int>(), 0) << node.dump();
  }
  const auto enable =
      access->brake_server().with_controller([](simdevices::PowderBrakeController& c) {
        return c.holding()[simdevices::brake_registers::control] &
               simdevices::brake_registers::control_enable;
      });
  EXPECT_EQ(enable, 0);
  EXPECT_FALSE(access->brake_server().with_controller(
      [](simdevices::PowderBrakeController& c) { return c.output_on(); }));

  // /api/live: two reads apart, the second brings newer samples, every channel but the brake's
  // present.
  nlohmann::json first;
  do {
    first = client.get("/api/live?limit=10").body;
    if (!first["samples"].empty()) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  } while (std::chrono::steady_clock::now() < deadline);
  ASSERT_FALSE(first["samples"].empty()) << first.dump();
  const auto next = first["next"].get<std::uint64_t>();
  // At 1 kHz, 50 samples take 50 ms; a loaded machine may take longer (counts, not timing).
  nlohmann::json second;
  const auto live_deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
  do {
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    second = client.get("/api/live?since=" + std::to_string(next) + "&limit=1000").body;
  } while (second["samples"].size() <= 50U && std::chrono::steady_clock::now() < live_deadline);
  ASSERT_GT(second["samples"].size(), 50U) << "fewer than 50 new samples in 20 s";
  // Newer samples: the live sequence number and the SYNC time both advance.
  auto last_seq = first["samples"].back()["seq"].get<std::uint64_t>();
  auto last_time = first["samples"].back()["receive_time_ns"].get<std::int64_t>();
  // A cycle whose PDOs came after the next SYNC (the simulated devices share this machine's
  // cores on the real clock) has those channels marked missing and null, never a stale value;
  // most cycles are complete (on an idle machine all but one or two in a hundred).
  std::size_t complete = 0;
  for (const auto& sample : second["samples"]) {
    ASSERT_GT(sample["seq"].get<std::uint64_t>(), last_seq) << sample.dump();
    ASSERT_GT(sample["receive_time_ns"].get<std::int64_t>(), last_time) << sample.dump();
    last_seq = sample["seq"].get<std::uint64_t>();
    last_time = sample["receive_time_ns"].get<std::int64_t>();
    const auto flags = sample["flags"].get<std::uint32_t>();
    for (const auto& [channel, bit] : {std::pair{"theta_in_rad", storage::kThetaInValid},
                                       std::pair{"theta_out_rad", storage::kThetaOutValid},
                                       std::pair{"torque_nm", storage::kTorqueValid}})
      ASSERT_EQ(sample[channel].is_number(), (flags & bit) != 0)
          << channel << " in " << sample.dump();
    if ((flags & storage::kAllChannelsValid) == storage::kAllChannelsValid) ++complete;
  }
  EXPECT_GT(complete, 50U);
  EXPECT_GE(complete * 2, second["samples"].size())
      << complete << " complete of " << second["samples"].size();
  std::printf("%zu of %zu live samples complete\n", complete, second["samples"].size());
  daemon.shutdown("test done");
}

}  // namespace
}  // namespace wavebench::daemon::testing
