// execute_run on the plant bench: the run folder, samples on disk as acquired, results.json,
// pass/fail, an operator stop from another thread, and bad requests that create nothing.
#include "wavebench/procedures/run_executor.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <filesystem>
#include <fstream>
#include <thread>

#include "../support/simulated_devices_gear.hpp"
#include "plant_bench.hpp"
#include "wavebench/procedures/run_limits.hpp"
#include "wavebench/simdevices/bench_plant.hpp"
#include "wavebench/storage/sample_log.hpp"

namespace wavebench::procedures {
namespace {

namespace fs = std::filesystem;

class RunExecutorTest : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = fs::temp_directory_path() /
            ("wavebench-runs-" + std::to_string(::getpid()) + "-" +
             ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(root_);
    store_ = std::make_unique<storage::RunStore>(root_, "test");
  }
  void TearDown() override {
    store_.reset();
    fs::remove_all(root_);
  }
  fs::path root_;
  std::unique_ptr<storage::RunStore> store_;
};

RunRequest small_static() {
  RunRequest r;
  r.procedure = "static";
  r.options = {{"positions", 4},
               {"loads_nm", {0, 30}},
               {"window_s", 0.1},
               {"limits", {{"static_p2p_arcmin", 20.0}}},
               {"calibrate_twin", false}};
  r.config_text = "name: plant\n";
  r.twin = false;
  r.report = false;
  return r;
}

TEST_F(RunExecutorTest, StaticRunWritesEverySampleResultsAndAVerdict) {
  testing::PlantBench bench(wavebench::testing::simulated_devices_gear());
  bench.connect();
  const std::uint64_t before = bench.acquisition_stats().samples;
  std::vector<RunProgress> progress;
  const auto out = execute_run(bench, *store_, small_static(),
                               [&](const RunProgress& p) { progress.push_back(p); });
  EXPECT_EQ(out.status, storage::RunStatus::kComplete);
  EXPECT_EQ(bench.deactivations(), 1);  // the drive is powered down when the run ends
  ASSERT_FALSE(progress.empty());
  EXPECT_EQ(progress.back().fraction, 1.0);
  EXPECT_EQ(progress.front().run_id, out.run_id);

  const auto log = storage::read_sample_log(store_->paths(out.run_id).samples);
  EXPECT_EQ(log.samples.size(), bench.acquisition_stats().samples - before);
  EXPECT_EQ(log.torn_tail_bytes, 0u);

  std::ifstream in(store_->paths(out.run_id).results);
  const auto results = nlohmann::json::parse(in);
  EXPECT_EQ(results["schema"], kResultsSchema);
  ASSERT_EQ(results["static"].size(), 4u);
  EXPECT_EQ(results["static"][0]["points"].size(), 4u);
  EXPECT_EQ(results["acquisition"]["samples_logged"], log.samples.size());
  EXPECT_EQ(results["pass"], true);
  EXPECT_EQ(results["gear"]["ratio"], 100.0);
  const auto record = store_->find_run(out.run_id);
  ASSERT_TRUE(record);
  EXPECT_EQ(record->status, storage::RunStatus::kComplete);
  ASSERT_TRUE(record->pass);
  EXPECT_TRUE(*record->pass);
  EXPECT_EQ(record->procedure, "static");
  EXPECT_EQ(record->unit_serial, "PLANT-TEST");
  EXPECT_TRUE(results["operator"].is_null());
}

TEST_F(RunExecutorTest, TheRequestsUnitSerialAndOperatorAreRecorded) {
  testing::PlantBench bench(wavebench::testing::simulated_devices_gear());
  bench.connect();
  auto request = small_static();
  request.unit_serial = "CSF25-100/2026-0042";
  request.operator_name = "Anna Müller";
  const auto out = execute_run(bench, *store_, request);
  EXPECT_EQ(out.results["unit_serial"], "CSF25-100/2026-0042");
  EXPECT_EQ(out.results["operator"], "Anna Müller");
  const auto record = store_->find_run(out.run_id);
  ASSERT_TRUE(record);
  EXPECT_EQ(record->unit_serial, "CSF25-100/2026-0042");
}

TEST_F(RunExecutorTest, ATightLimitFailsTheRun) {
  testing::PlantBench bench(wavebench::testing::simulated_devices_gear());
  bench.connect();
  auto request = small_static();
  request.options["limits"] = {{"static_p2p_arcmin", 1.0}};
  const auto out = execute_run(bench, *store_, request);
  EXPECT_EQ(out.results["pass"], false);
  const auto record = store_->find_run(out.run_id);
  ASSERT_TRUE(record && record->pass);
  EXPECT_FALSE(*record->pass);
}

TEST_F(RunExecutorTest, AnOperatorStopFromAnotherThreadAbortsWithTheReasonAndKeepsTheSamples) {
  testing::PlantBench bench(wavebench::testing::simulated_devices_gear());
  bench.connect();
  std::atomic<bool> reverse_started{false};
  std::thread operator_thread([&] {
    while (!reverse_started) std::this_thread::yield();
    bench.request_stop("operator stop");
  });
  const auto out = execute_run(bench, *store_, small_static(), [&](const RunProgress& p) {
    if (p.phase.find("reverse") != std::string::npos) reverse_started = true;
  });
  operator_thread.join();
  EXPECT_EQ(out.status, storage::RunStatus::kAborted);
  EXPECT_EQ(out.reason, "operator stop");
  EXPECT_EQ(bench.state(), bench::BenchLifecycle::kFault);
  EXPECT_EQ(bench.brake_setting(), 0.0);  // safe state
  EXPECT_EQ(bench.deactivations(), 1);

  const auto record = store_->find_run(out.run_id);
  ASSERT_TRUE(record);
  EXPECT_EQ(record->status, storage::RunStatus::kAborted);
  EXPECT_EQ(record->reason, "operator stop");
  const auto log = storage::read_sample_log(store_->paths(out.run_id).samples);
  EXPECT_GT(log.samples.size(), 1000u);  // the whole forward pass and more
  EXPECT_FALSE(log.corrupt_record);
  EXPECT_EQ(out.results["status"], "aborted");
  EXPECT_EQ(out.results["reason"], "operator stop");
  // The finished forward pass is kept, marked as from an aborted run (issue #22); no verdict.
  ASSERT_TRUE(out.results.contains("partial")) << out.results.dump().substr(0, 400);
  EXPECT_EQ(out.results["partial"]["finished"], 1);
  ASSERT_EQ(out.results["static"].size(), 1u);
  EXPECT_EQ(out.results["static"][0]["direction"], "forward");
  EXPECT_TRUE(out.results["verdict"].is_null());
}

TEST_F(RunExecutorTest, ASafetyTripMidRunIsAnAbortNotAnException) {
  testing::PlantBenchOptions o;
  o.trip_at_s = 3.0;
  o.trip_reason = "over-torque: 151 N·m > 150 N·m";
  testing::PlantBench bench(wavebench::testing::simulated_devices_gear(), o);
  bench.connect();
  RunRequest r = small_static();
  r.procedure = "lost-motion";
  r.options = nlohmann::json::object();
  const auto out = execute_run(bench, *store_, r);
  EXPECT_EQ(out.status, storage::RunStatus::kAborted);
  EXPECT_EQ(out.reason, o.trip_reason);
  EXPECT_EQ(bench.deactivations(), 1);
  const auto log = storage::read_sample_log(store_->paths(out.run_id).samples);
  EXPECT_NEAR(static_cast<double>(log.samples.size()), 3000, 5);
}

TEST_F(RunExecutorTest, BadRequestsNameTheKeyAndCreateNothing) {
  testing::PlantBench bench(wavebench::testing::simulated_devices_gear());
  bench.connect();
  const auto expect_refused = [&](RunRequest r, const std::string& needle) {
    try {
      execute_run(bench, *store_, r);
      ADD_FAILURE() << "accepted " << r.options.dump();
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
    }
  };
  auto r = small_static();
  r.options["positions"] = "many";
  expect_refused(r, "static.positions");
  r = small_static();
  r.procedure = "wobble";
  expect_refused(r, "procedure");
  r = small_static();
  r.options["limits"] = {{"p2p", 3}};
  expect_refused(r, "limits.p2p");
  r = small_static();
  r.procedure = "dynamic";
  r.options = {{"input_rpm", -5}};
  expect_refused(r, "dynamic.input_rpm");
  r = small_static();
  r.unit_serial = "SN 42";  // a space: not what a barcode holds
  expect_refused(r, "unit_serial: got 'SN 42', expected 1 to 64 of");
  r = small_static();
  r.unit_serial = std::string(65, 'A');
  expect_refused(r, "unit_serial");
  r = small_static();
  r.operator_name = "Eve<script>";
  expect_refused(r, "operator: got 'Eve<script>'");
  r = small_static();
  r.operator_name = "tab\there";
  expect_refused(r, "operator");
  EXPECT_TRUE(store_->list_runs().empty());
  std::size_t entries = 0;
  for (const auto& e : fs::directory_iterator(root_)) {
    if (e.is_directory()) ++entries;
  }
  EXPECT_EQ(entries, 0u);
}

}  // namespace
}  // namespace wavebench::procedures

namespace wavebench::procedures {
namespace {

TEST_F(RunExecutorTest, TheTwinRunsBesideAndTheReportIsWritten) {
  testing::PlantBench bench(wavebench::testing::simulated_devices_gear());
  bench.connect();
  auto request = small_static();
  request.twin = true;
  request.report = true;
  // Calibration replays the twin over the whole run: minutes, the twin's own tests cover it.
  request.options["calibrate_twin"] = false;
  const auto out = execute_run(bench, *store_, request);
  ASSERT_EQ(out.status, storage::RunStatus::kComplete);
  ASSERT_TRUE(out.results.contains("twin"));
  EXPECT_FALSE(out.results["twin"].contains("error")) << out.results["twin"]["error"];
  EXPECT_TRUE(fs::exists(out.dir / "twin.csv"));
  EXPECT_EQ(out.results["twin"]["samples_received"], out.results["acquisition"]["samples_logged"]);
  EXPECT_TRUE(out.results["twin"].contains("residual"));
  ASSERT_TRUE(out.results.contains("report")) << out.results.value("report_error", "");
  EXPECT_TRUE(fs::exists(out.dir / "report.html"));
}

}  // namespace
}  // namespace wavebench::procedures

namespace wavebench::procedures {
namespace {

TEST(RunLimits, StaticLostMotionIsLimitedBySizeWhateverItsSign) {
  const nlohmann::json results = {
      {"lost_motion",
       {{{"load_nm", 60}, {"lost_motion_arcmin", {-10.4, -10.2}}, {"max_abs_arcmin", 10.4}}}}};
  auto v = check_limits({{"static_lost_motion_arcmin", 5.0}}, results);
  ASSERT_TRUE(v.pass);
  EXPECT_FALSE(*v.pass);
  EXPECT_DOUBLE_EQ(v.checks[0]["measured"].get<double>(), 10.4);
  v = check_limits({{"static_lost_motion_arcmin", 11.0}}, results);
  EXPECT_TRUE(v.pass && *v.pass);
  EXPECT_FALSE(check_limits({{"dynamic_rms_arcsec", 1.0}}, results).pass.has_value());
}

}  // namespace
}  // namespace wavebench::procedures
