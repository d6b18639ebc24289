// `wavebench report` as a user runs it: one run or several (an index then), a run store root
// standing for its runs, --out, and a folder that is not a run exits 2 naming it, writing
// nothing.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "../support/cli_run.hpp"
#include "wavebench/storage/run_store.hpp"

namespace {

namespace fs = std::filesystem;
namespace storage = wavebench::storage;
using nlohmann::json;

using wavebench::testing::CliRun;
using wavebench::testing::run_cli;

std::string q(const fs::path& p) {
  return "'" + p.string() + "'";
}

class ReportCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("wavebench-report-cli-" + std::to_string(::getpid()) + "-" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    storage::RunStore store(dir_ / "runs", "wavebench test");
    static_id_ = store.create_run("static", "SN-1", "bench: sim\n");
    store.write_results(
        static_id_,
        {{"static",
          {{{"direction", "forward"},
            {"load_nm", 0},
            {"mean_arcmin", -1.62},
            {"p2p_arcmin", 5.21},
            {"std_arcmin", 1.83},
            {"points", {{{"position", 0}, {"output_angle_deg", 0}, {"te_arcmin", -1.6}}}}}}}});
    store.finish_run(static_id_, storage::RunStatus::kComplete);
    aborted_id_ = store.create_run("dynamic", "SN-1", "bench: sim\n");
    store.finish_run(aborted_id_, storage::RunStatus::kAborted, "Modbus link lost");
  }
  void TearDown() override { fs::remove_all(dir_); }

  fs::path dir_;
  std::string static_id_, aborted_id_;
};

TEST_F(ReportCli, SeveralRunsGetAReportEachAndAnIndex) {
  const fs::path a = dir_ / "runs" / static_id_, b = dir_ / "runs" / aborted_id_;
  const CliRun r = run_cli("report " + q(a) + " " + q(b), dir_ / "log.txt");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(fs::exists(a / "report.html"));
  EXPECT_TRUE(fs::exists(b / "report.html"));
  EXPECT_TRUE(fs::exists(dir_ / "runs" / "index.html"));
  EXPECT_NE(r.output.find("Static TE per direction and load"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("-1.62"), std::string::npos);
  EXPECT_NE(r.output.find("aborted: Modbus link lost"), std::string::npos);
  EXPECT_NE(r.output.find("session report: "), std::string::npos);
  EXPECT_NE(r.output.find("index.html"), std::string::npos);
}

TEST_F(ReportCli, AStoreRootStandsForItsRunsAndOutGathersTheReports) {
  const fs::path out = dir_ / "reports";
  const CliRun r = run_cli("report " + q(dir_ / "runs") + " --out " + q(out), dir_ / "log.txt");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(fs::exists(out / static_id_ / "report.html"));
  EXPECT_TRUE(fs::exists(out / aborted_id_ / "report.html"));
  EXPECT_TRUE(fs::exists(out / "index.html"));
  EXPECT_FALSE(fs::exists(dir_ / "runs" / static_id_ / "report.html"));
}

TEST_F(ReportCli, NotARunFolderExits2AndWritesNothing) {
  fs::create_directories(dir_ / "empty");
  const fs::path good = dir_ / "runs" / static_id_;
  CliRun r = run_cli("report " + q(good) + " " + q(dir_ / "empty"), dir_ / "log.txt");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("empty"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("holds none of status.json"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(good / "report.html"));

  r = run_cli("report " + q(dir_ / "nowhere"), dir_ / "log.txt");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("not a directory"), std::string::npos) << r.output;

  r = run_cli("report", dir_ / "log.txt");  // RUN_DIR is required
  EXPECT_EQ(r.exit_code, 2) << r.output;
}

}  // namespace
