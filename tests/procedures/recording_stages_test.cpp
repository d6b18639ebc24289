// The recording's stages alone (issue #23): each started on a context made by hand, fed
// samples through its observe hook, finished and closed, without a procedure or the loop.
#include "recording_stages.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>

#include "../support/simulated_devices_gear.hpp"
#include "plant_bench.hpp"
#include "wavebench/simdevices/bench_plant.hpp"
#include "wavebench/storage/run_store.hpp"
#include "wavebench/storage/sample_log.hpp"

namespace wavebench::procedures {
namespace {

class RecordingStagesTest : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = std::filesystem::temp_directory_path() /
            ("wavebench-recording-stages-" + std::to_string(::getpid()) + "-" +
             ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::remove_all(root_);
    store_ = std::make_unique<storage::RunStore>(root_, "test");
  }
  void TearDown() override {
    store_.reset();
    std::filesystem::remove_all(root_);
  }

  std::unique_ptr<RunContext> context(bool twin) {
    RunRequest request;
    request.procedure = "dynamic";
    request.twin = twin;
    request.report = false;
    auto c = std::make_unique<RunContext>(parse_request(request));
    c->request = request;
    c->description = bench_.description();
    c->store = store_.get();
    c->unit_serial = "U1";
    c->outcome.run_id = store_->create_run("dynamic", "U1", "config", c->parsed.limits.dump());
    c->paths = store_->paths(c->outcome.run_id);
    return c;
  }

  // A gear turning slowly at no load: every core channel valid.
  static storage::SyncSample sample(std::uint32_t i) {
    storage::SyncSample s;
    s.sync_counter = i + 1;
    s.flags = storage::kAllChannelsValid;
    s.receive_time_ns = static_cast<std::int64_t>(i) * 1'000'000;
    s.theta_in_rad = 0.01 * i;
    s.theta_out_rad = 0.01 * i / 80.0;
    s.input_speed_rad_s = 10.0;
    return s;
  }

  std::filesystem::path root_;
  std::unique_ptr<storage::RunStore> store_;
  testing::PlantBench bench_{wavebench::testing::simulated_devices_gear()};
};

TEST_F(RecordingStagesTest, TheLoopsStagesInOrderHeadLogTwin) {
  const auto stages = recording_stages();
  ASSERT_EQ(stages.size(), 3u);
  EXPECT_STREQ(stages[0]->name(), "results head");
  EXPECT_STREQ(stages[1]->name(), "sample log");
  EXPECT_STREQ(stages[2]->name(), "twin beside the bench");
}

TEST_F(RecordingStagesTest, ResultsHeadNamesTheRunTheBenchAndTheUnitAndObservesNothing) {
  auto c = context(false);
  ResultsHeadStage stage;
  stage.start(*c, bench_);
  EXPECT_FALSE(stage.observes());
  EXPECT_EQ(c->results["schema"], kResultsSchema);
  EXPECT_EQ(c->results["run_id"], c->outcome.run_id);
  EXPECT_EQ(c->results["procedure"], "dynamic");
  EXPECT_EQ(c->results["unit_serial"], "U1");
  EXPECT_EQ(c->results["bench"], "plant");
  EXPECT_TRUE(c->complete());
}

TEST_F(RecordingStagesTest, SampleLogWritesEverySampleItObservesAndCountsThem) {
  auto c = context(false);
  SampleLogStage stage;
  stage.start(*c, bench_);
  ASSERT_TRUE(c->complete()) << c->outcome.reason;
  ASSERT_TRUE(stage.observes());
  for (std::uint32_t i = 0; i < 250; ++i) stage.on_sample(sample(i));
  stage.finish(*c);
  stage.close(*c, bench_);
  EXPECT_TRUE(c->complete()) << c->outcome.reason;
  EXPECT_FALSE(stage.trip_reason());
  EXPECT_EQ(c->samples, 250u);
  EXPECT_EQ(c->results["acquisition"]["samples_logged"], 250);
  EXPECT_EQ(c->results["acquisition"]["log_queue_dropped"], 0);
  const auto page = storage::read_sample_log_page(c->paths.samples, 0, 1000);
  ASSERT_EQ(page.samples.size(), 250u);
  EXPECT_DOUBLE_EQ(page.samples[249].theta_in_rad, 2.49);
}

TEST_F(RecordingStagesTest, ASampleLogThatCannotBeCreatedAbortsBeforeAnythingMoves) {
  auto c = context(false);
  c->paths.samples = root_ / "no such folder" / "samples.wbs";
  SampleLogStage stage;
  stage.start(*c, bench_);
  EXPECT_FALSE(c->complete());
  EXPECT_NE(c->outcome.reason.find("sample log not created, nothing moved"), std::string::npos)
      << c->outcome.reason;
  EXPECT_FALSE(stage.observes());
  stage.finish(*c);  // nothing to drain or close: no throw, no results
  stage.close(*c, bench_);
  EXPECT_FALSE(c->results.contains("acquisition"));
}

TEST_F(RecordingStagesTest, TwinOffObservesNothingAndStartsNoTwin) {
  auto c = context(false);
  TwinBesideBenchStage stage;
  stage.start(*c, bench_);
  EXPECT_FALSE(stage.observes());
  EXPECT_EQ(c->twin_beside, nullptr);
  EXPECT_EQ(c->twin_source["kind"], "nominal");
}

TEST_F(RecordingStagesTest, TwinOnTakesEverySampleItObserves) {
  auto c = context(true);
  TwinBesideBenchStage stage;
  stage.start(*c, bench_);
  ASSERT_TRUE(stage.observes()) << c->twin_json.dump();
  ASSERT_NE(c->twin_beside, nullptr);
  for (std::uint32_t i = 0; i < 120; ++i) stage.on_sample(sample(i));
  // Drained by the post-run "twin" stage in a run; here by hand.
  const auto& report = c->twin_beside->finish();
  EXPECT_EQ(report.samples_received, 120u);
  EXPECT_EQ(report.samples_dropped, 0u);
}

}  // namespace
}  // namespace wavebench::procedures
