// `wavebench twin` (and its old name `sim`) as a user runs it: files, JSON keys, the physics of the
// largest line, and that a bad config writes nothing and exits 2.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "../support/cli_run.hpp"

namespace {

namespace fs = std::filesystem;
const fs::path kConfigs = fs::path(WAVEBENCH_SOURCE_DIR) / "configs" / "twin";

using wavebench::testing::CliRun;
using wavebench::testing::run_cli;

class SimCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("wavebench-sim-cli-" + std::to_string(::getpid()) + "-" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

TEST_F(SimCli, ShortXb80RunWritesEveryFileWithTheSummaryKeys) {
  const fs::path out = dir_ / "xb";
  const CliRun r = run_cli("twin '" + (kConfigs / "xb-80-134h.yaml").string() + "' --out '" +
                               out.string() + "' --t-end 0.4 --quiet",
                           dir_ / "log.txt");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  for (const char* f : {"timeseries.csv", "summary.json", "time_response.png", "spectrum.png",
                        "phase_portrait.png", "poincare.png"}) {
    EXPECT_TRUE(fs::exists(out / f)) << f;
    if (fs::exists(out / f)) {
      EXPECT_GT(fs::file_size(out / f), 100u) << f;
    }
  }
  // Nothing left behind beside the result.
  int entries = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir_)) ++entries;
  EXPECT_EQ(entries, 2) << "only xb/ and the log";

  std::ifstream js(out / "summary.json");
  const auto j = nlohmann::json::parse(js);
  for (const char* key : {"peaks", "motion", "natural_frequencies_hz", "sim_time_s", "steps",
                          "rhs_evaluations", "wall_s"}) {
    EXPECT_TRUE(j.contains(key)) << key;
  }
  ASSERT_TRUE(j["peaks"].is_array());
  ASSERT_FALSE(j["peaks"].empty());
  const auto& top = j["peaks"][0];
  EXPECT_TRUE(top.contains("freq_hz"));
  EXPECT_TRUE(top.contains("amplitude"));
  ASSERT_TRUE(top.contains("sources"));
  // The largest output line is the 2(1+1/N) f_H = 90.0 Hz line of the tangential errors.
  // (0.2 s of record gives 5 Hz bins: 89.33 and 90.0 merge, 44.67 does not.)
  EXPECT_NEAR(top["freq_hz"].get<double>(), 90.0, 5.0);
  ASSERT_FALSE(top["sources"].empty());
  const std::string first_source = top["sources"][0]["source"].get<std::string>();
  EXPECT_TRUE(first_source.rfind("dF_i1", 0) == 0 || first_source.rfind("dF_i3", 0) == 0 ||
              first_source.rfind("T1k", 0) == 0)
      << first_source;
  EXPECT_GT(j["steps"].get<long>(), 0);
  EXPECT_GT(j["rhs_evaluations"].get<long>(), j["steps"].get<long>());
  EXPECT_TRUE(j["motion"].contains("class"));

  std::ifstream csv(out / "timeseries.csv");
  std::string header, line;
  std::getline(csv, header);
  EXPECT_EQ(header.rfind("t_s,", 0), 0u);
  EXPECT_NE(header.find("te_arcsec"), std::string::npos);
  long rows = 0;
  while (std::getline(csv, line)) ++rows;
  const double record = j["sim_time_s"].get<double>();
  EXPECT_NEAR(static_cast<double>(rows), record * 60000.0 + 1, 2.0);
}

TEST_F(SimCli, BadConfigExitsTwoAndCreatesNothing) {
  std::ifstream in(kConfigs / "xb-80-134h.yaml");
  std::stringstream text;
  text << in.rdbuf();
  std::string yaml = text.str();
  const std::string from = "k0: \"2.0e5 N*m/rad\"";
  ASSERT_NE(yaml.find(from), std::string::npos);
  yaml.replace(yaml.find(from), from.size(), "k0: \"2.0e5 N*m\"");
  const fs::path bad = dir_ / "bad.yaml";
  std::ofstream(bad) << yaml;

  const fs::path out = dir_ / "never";
  const CliRun r =
      run_cli("sim '" + bad.string() + "' --out '" + out.string() + "'", dir_ / "log.txt");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_FALSE(fs::exists(out));
  EXPECT_NE(r.output.find("stiffness.k0"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("2.0e5 N*m"), std::string::npos) << r.output;
  int entries = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir_)) ++entries;
  EXPECT_EQ(entries, 2) << "only bad.yaml and the log";
}

TEST_F(SimCli, MissingConfigFileExitsTwo) {
  const CliRun r =
      run_cli("sim '" + (dir_ / "absent.yaml").string() + "' --out '" + (dir_ / "o").string() + "'",
              dir_ / "log.txt");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_FALSE(fs::exists(dir_ / "o"));
}

TEST_F(SimCli, MissingOutOptionIsAUsageError) {
  const CliRun r =
      run_cli("sim '" + (kConfigs / "xb-80-134h.yaml").string() + "'", dir_ / "log.txt");
  EXPECT_EQ(r.exit_code, 2) << r.output;
}

}  // namespace

namespace {

// The whole shipped XB-80 case: the seeds' ranking of the output lines (seed 000 Table 3).
TEST_F(SimCli, FullXb80RunKeepsTheSeedRanking) {
  const fs::path out = dir_ / "xb";
  const CliRun r = run_cli(
      "twin '" + (kConfigs / "xb-80-134h.yaml").string() + "' --out '" + out.string() + "' --quiet",
      dir_ / "log.txt");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  std::ifstream js(out / "summary.json");
  const auto j = nlohmann::json::parse(js);
  auto amplitude_at = [&](double f, double tol) {
    double a = 0;
    for (const auto& p : j["peaks"]) {
      if (std::abs(p["freq_hz"].get<double>() - f) < tol) {
        a = std::max(a, p["amplitude"].get<double>());
      }
    }
    return a;
  };
  const double a90 = amplitude_at(90.0, 0.1);
  const double a89 = amplitude_at(89.333, 0.1);
  const double a44 = amplitude_at(44.667, 0.1);
  const double amesh = amplitude_at(24120.0, 1.0);
  EXPECT_NEAR(j["peaks"][0]["freq_hz"].get<double>(), 90.0, 0.05);
  EXPECT_GT(a89, 0.0) << "89.33 Hz resolved next to 90.0 Hz";
  EXPECT_GT(a90, 3 * a89);
  EXPECT_GT(a89, 10 * a44);
  EXPECT_GT(amesh, 0.0);
  EXPECT_LT(amesh, 0.2 * a90);
}

}  // namespace
