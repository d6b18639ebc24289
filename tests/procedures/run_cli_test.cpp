// `wavebench run` as a user runs it on the in-process simulated bench: the summary table and
// where results and report are; bad options and configs exit 2 naming them, writing nothing.
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

namespace {

namespace fs = std::filesystem;

using wavebench::testing::CliRun;
using wavebench::testing::run_cli;

class RunCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("wavebench-run-cli-" + std::to_string(::getpid()) + "-" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  CliRun run(const std::string& args) { return run_cli("run " + args, dir_ / "cli.log"); }
  fs::path dir_;
};

TEST_F(RunCli, StaticOnTheSimulatedBenchPrintsTheSummaryAndWhereTheResultsAre) {
  const fs::path out = dir_ / "runs";
  const auto r = run("static --bench sim --out '" + out.string() +
                     "' --positions 4 --loads 0,30 --window 0.1 --no-twin --no-report --quiet");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("forward"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("reverse"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("p2p [arcmin]"), std::string::npos) << r.output;
  const auto at = r.output.find("results: ");
  ASSERT_NE(at, std::string::npos) << r.output;
  const std::string path = r.output.substr(at + 9, r.output.find('\n', at) - at - 9);
  std::ifstream in(path);
  ASSERT_TRUE(in) << path;
  const auto results = nlohmann::json::parse(in);
  ASSERT_EQ(results["static"].size(), 4u);
  EXPECT_EQ(results["static"][3]["load_nm"], 30.0);
  EXPECT_EQ(results["status"], "complete");
}

// A bench config with an input-side CiA 406 encoder (configs/benches/sim-input-encoder.yaml):
// the run records the extra channel, named in results.json and in the sample log's header.
TEST_F(RunCli, AnInputSideEncoderInTheBenchConfigIsRecordedAsAChannel) {
  const fs::path out = dir_ / "runs";
  const fs::path config = fs::path(WAVEBENCH_SOURCE_DIR) / "configs/benches/sim-input-encoder.yaml";
  const auto r = run("static --bench '" + config.string() + "' --out '" + out.string() +
                     "' --positions 4 --loads 0 --window 0.1 --no-twin --no-report --quiet");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto at = r.output.find("results: ");
  ASSERT_NE(at, std::string::npos) << r.output;
  const fs::path results_path = r.output.substr(at + 9, r.output.find('\n', at) - at - 9);
  std::ifstream in(results_path);
  const auto results = nlohmann::json::parse(in);
  ASSERT_EQ(results["extra_channels"].size(), 1u) << results.dump();
  EXPECT_EQ(results["extra_channels"][0]["name"], "theta_in_encoder");
  std::ifstream log(results_path.parent_path() / "samples.wbs", std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(log)), std::istreambuf_iterator<char>());
  ASSERT_GT(bytes.size(), 72u + 48 * 7);
  EXPECT_EQ(bytes[8], 2);  // version 2
  EXPECT_EQ(std::string(bytes.c_str() + 72 + 48 * 6), "theta_in_encoder");
}

TEST_F(RunCli, BadOptionsExitTwoNamingKeyValueAndExpectationAndWriteNothing) {
  const fs::path out = dir_ / "runs";
  const std::string o = " --out '" + out.string() + "' --quiet";
  auto r = run("static --bench sim --positions 1" + o);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("static.positions: got '1', expected an integer from 2"),
            std::string::npos)
      << r.output;
  r = run("static --bench sim --rpm 100" + o);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("--rpm"), std::string::npos) << r.output;
  r = run("dynamic --bench sim --option input_rpm=-3" + o);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("dynamic.input_rpm"), std::string::npos) << r.output;
  r = run("static --bench sim --limit p2p=3" + o);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("limits.p2p"), std::string::npos) << r.output;
  r = run("wobble --bench sim" + o);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  r = run("static --bench '" + (dir_ / "missing.yaml").string() + "'" + o);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("missing.yaml"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(out));
}

}  // namespace
