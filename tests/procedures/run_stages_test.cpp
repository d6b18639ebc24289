// The run's stages alone (issue #21, #23): the recording's time-based progress, and the
// post-run stages that decide the verdict and write results.json on a context made by hand.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "post_run_stages.hpp"
#include "recording_clock.hpp"
#include "run_context.hpp"

namespace wavebench::procedures {
namespace {

TEST(RecordingClock, BeforeThePaceIsKnownThePlanSaysWhatIsLeft) {
  RecordingClock clock(20.0);
  const auto p = clock.at(0, 0);
  EXPECT_GE(p.remaining_s, 20.0);
  EXPECT_DOUBLE_EQ(p.fraction, 0);
}

TEST(RecordingClock, ASlowerPaceThanPlannedWins) {
  RecordingClock clock(10.0);
  // A fast run-in to 5 %, then 45 % more in 20 s: at least another 20 s, whatever the plan said.
  clock.at(0.05, 0.2);
  const auto p = clock.at(0.5, 20.2);
  EXPECT_GE(p.remaining_s, 20.0);
  EXPECT_NEAR(p.fraction, 20.2 / (20.2 + p.remaining_s), 1e-12);
}

TEST(RecordingClock, DoneIsDone) {
  RecordingClock clock(10.0);
  EXPECT_DOUBLE_EQ(clock.at(1.0, 12.0).remaining_s, 0);
  EXPECT_DOUBLE_EQ(clock.at(1.0, 12.0).fraction, 1.0);
}

class PostRunStagesTest : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = std::filesystem::temp_directory_path() /
            ("wavebench-stages-" + std::to_string(::getpid()) + "-" +
             ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::remove_all(root_);
    store_ = std::make_unique<storage::RunStore>(root_, "test");
  }
  void TearDown() override {
    store_.reset();
    std::filesystem::remove_all(root_);
  }

  std::unique_ptr<RunContext> context(const nlohmann::json& limits) {
    RunRequest request;
    request.procedure = "dynamic";
    request.options = {{"limits", limits}};
    request.twin = false;
    request.report = false;
    auto c = std::make_unique<RunContext>(parse_request(request));
    c->request = request;
    c->store = store_.get();
    c->unit_serial = "U1";
    c->outcome.run_id = store_->create_run("dynamic", "U1", "config", c->parsed.limits.dump());
    c->paths = store_->paths(c->outcome.run_id);
    c->results = {{"run_id", c->outcome.run_id}, {"procedure", "dynamic"}};
    c->procedure_result.json = {{"dynamic", {{"te_peak_to_peak_arcsec", 10.0}}}};
    return c;
  }

  std::filesystem::path root_;
  std::unique_ptr<storage::RunStore> store_;
};

TEST_F(PostRunStagesTest, EveryStageHasAnEstimateAndOnlyWhatRunsCostsTime) {
  auto c = context(nlohmann::json::object());
  c->samples = 100000;
  ASSERT_EQ(post_run_stages().size(), 7u);
  double total = 0;
  for (const auto& stage : post_run_stages()) total += stage.estimate_s(*c);
  // No twin, no report: only the results' write is left.
  EXPECT_GT(total, 0);
  EXPECT_LT(total, 2.0);
}

TEST_F(PostRunStagesTest, ProcessingUntilTheResultsAreWrittenThenComplete) {
  auto c = context(nlohmann::json::object());
  mark_processing(*c);
  std::ifstream interim(c->paths.results);
  EXPECT_EQ(nlohmann::json::parse(interim)["status"], "processing");
  EXPECT_EQ(store_->find_run(c->outcome.run_id)->status, storage::RunStatus::kRunning);
  decide_verdict(*c);
  write_results(*c);
  // On disk, status.json as it will be; the index says running until the end is recorded.
  EXPECT_EQ(store_->find_run(c->outcome.run_id)->status, storage::RunStatus::kRunning);
  std::ifstream status_file(c->paths.status);
  EXPECT_EQ(nlohmann::json::parse(status_file)["status"], "complete");
  record_end(*c);
  EXPECT_EQ(store_->find_run(c->outcome.run_id)->status, storage::RunStatus::kComplete);
  std::ifstream final_file(c->paths.results);
  EXPECT_EQ(nlohmann::json::parse(final_file)["status"], "complete");
}

TEST_F(PostRunStagesTest, ResultsThatCannotBeWrittenMakeTheRunAbortedNotPass) {
  auto c = context(nlohmann::json::object());
  decide_verdict(*c);
  // A directory where results.json goes: the write fails as on a broken disk.
  std::filesystem::remove(c->paths.results);
  std::filesystem::create_directories(c->paths.results);
  write_results(*c);
  record_end(*c);
  const auto row = store_->find_run(c->outcome.run_id);
  ASSERT_TRUE(row);
  EXPECT_EQ(row->status, storage::RunStatus::kAborted);
  EXPECT_FALSE(row->pass.has_value());
  EXPECT_NE(row->reason.find("results.json not written"), std::string::npos) << row->reason;
  EXPECT_EQ(c->outcome.status, storage::RunStatus::kAborted);
  EXPECT_TRUE(c->results["verdict"].is_null());
}

TEST_F(PostRunStagesTest, AnAbortedRecordingHasNoVerdict) {
  auto c = context(nlohmann::json::object());
  c->abort_with("operator stop");
  decide_verdict(*c);
  EXPECT_EQ(c->results["status"], "aborted");
  EXPECT_EQ(c->results["reason"], "operator stop");
  EXPECT_TRUE(c->results["verdict"].is_null());
  EXPECT_FALSE(c->results.contains("limit_checks"));
}

}  // namespace
}  // namespace wavebench::procedures
