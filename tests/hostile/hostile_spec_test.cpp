// Hostile and careless product specs (configs/specs/*.yaml) and spec names in run requests:
// a bad file is refused with a message naming the file, the key, the value and what was
// expected; a bad name is refused naming `spec` and the known specs, before anything is created.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "cli_run.hpp"
#include "wavebench/procedures/product_spec.hpp"

namespace wavebench::procedures {
namespace {

namespace fs = std::filesystem;

struct BadSpec {
  std::string yaml;
  std::vector<std::string> expected_in_message;  // beside the file's path
};

const char* kGood = "model: M\nlimits:\n  static_te_p2p: 1 arcmin\n";

std::vector<BadSpec> bad_specs() {
  return {
      {"model: M\nlimits:\n  static_te_p2q: 1 arcmin\n", {"limits.static_te_p2q", "1 arcmin"}},
      {"model: M\ncolour: red\nlimits:\n  static_te_p2p: 1 arcmin\n", {"colour", "red"}},
      {"model: M\nlimits:\n  static_te_p2p: 1 arcmn\n",
       {"limits.static_te_p2p", "arcmn", "an angle"}},
      {"model: M\nlimits:\n  min_k1: 5 arcmin\n", {"limits.min_k1", "5 arcmin", "stiffness"}},
      {"model: M\nlimits:\n  static_te_p2p: -1 arcmin\n",
       {"limits.static_te_p2p", "-1 arcmin", "a value > 0"}},
      {"model: M\nlimits:\n  dynamic_te_p2p: 0 arcsec\n",
       {"limits.dynamic_te_p2p", "0 arcsec", "a value > 0"}},
      {"model: M\nlimits:\n  static_te_p2p: 1\n", {"limits.static_te_p2p", "'1'", "with its unit"}},
      {"model: M\nlimits:\n  twin_residual_rms: .nan arcsec\n", {"limits.twin_residual_rms"}},
      {"model: M\nlimits:\n  static_te_p2p: 1 arcmin\n  lost_motion_at: 3 %\n",
       {"limits.lost_motion_at", "3 %", "without a lost_motion limit"}},
      {"model: M\nlimits:\n  lost_motion: 1 arcmin\n  lost_motion_at: 150 %\n",
       {"limits.lost_motion_at", "150 %", "(0, 100 %]"}},
      {"model: M\nlimits:\n  lost_motion: 1 arcmin\n  lost_motion_at: 0.03\n",
       {"limits.lost_motion_at", "0.03", "a percentage"}},
      {"limits:\n  static_te_p2p: 1 arcmin\n", {"model", "required"}},
      {"model: M\nlimits: {}\n", {"limits", "at least one limit"}},
      {"model: M\n", {"limits"}},
      {"- model\n- M\n", {"product spec"}},
      {"model: M\nlimits:\n  static_te_p2p:\n", {"limits.static_te_p2p"}},
  };
}

class HostileSpecs : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("wavebench-hostile-specs-" + std::to_string(::getpid()) + "-" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_ / "specs");
    write("good", kGood);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path write(const std::string& name, const std::string& text) const {
    const auto path = dir_ / "specs" / (name + ".yaml");
    std::ofstream(path) << text;
    return path;
  }
  fs::path dir_;
};

TEST_F(HostileSpecs, EveryBadSpecFileIsRefusedNamingFileKeyValueAndExpectation) {
  int tried = 0, refused = 0;
  for (const auto& bad : bad_specs()) {
    const auto path = write("bad", bad.yaml);
    ++tried;
    try {
      find_product_spec(dir_ / "specs", "bad");
      ADD_FAILURE() << bad.yaml << ": accepted";
    } catch (const std::invalid_argument& e) {
      ++refused;
      const std::string m = e.what();
      EXPECT_NE(m.find(path.string()), std::string::npos) << m;
      for (const auto& part : bad.expected_in_message) {
        EXPECT_NE(m.find(part), std::string::npos) << "'" << part << "' not in: " << m;
      }
    }
  }
  std::printf("%d hostile spec files, %d refused\n", tried, refused);
  EXPECT_EQ(refused, tried);
  EXPECT_NO_THROW(find_product_spec(dir_ / "specs", "good"));
}

TEST_F(HostileSpecs, BadSpecNamesAreRefusedNamingSpecAndTheKnownOnes) {
  write("other", kGood);
  fs::create_directories(dir_ / "secret");
  std::ofstream(dir_ / "secret" / "x.yaml") << kGood;
  const std::vector<std::string> names = {
      "../secret/x", "../x", "/etc/passwd", "a/b",     ".good",     "",     std::string(65, 'a'),
      "good spec",   "gööd", "good\n",      "unknown", "good.yaml", "GOOD", "x;rm -rf"};
  int refused = 0;
  for (const auto& name : names) {
    try {
      find_product_spec(dir_ / "specs", name);
      ADD_FAILURE() << "'" << name << "' accepted";
    } catch (const std::invalid_argument& e) {
      ++refused;
      const std::string m = e.what();
      EXPECT_EQ(m.rfind("spec: got '", 0), 0u) << m;
      EXPECT_NE(m.find("good, other"), std::string::npos) << m;
      EXPECT_LT(m.size(), 400u) << m;
    }
  }
  std::printf("%zu hostile spec names, %d refused\n", names.size(), refused);
  EXPECT_EQ(refused, static_cast<int>(names.size()));
  EXPECT_EQ(find_product_spec(dir_ / "specs", "other").name, "other");
}

TEST_F(HostileSpecs, TheCliRefusesABadSpecNameWithExit2AndCreatesNoRun) {
  for (const auto& name : std::vector<std::string>{"../x", "nope", std::string(80, 'z')}) {
    const auto run = wavebench::testing::run_cli(
        "run static --positions 2 --loads 0 --quiet --out '" + (dir_ / "runs").string() +
            "' --specs-dir '" + (dir_ / "specs").string() + "' --spec '" + name + "'",
        dir_ / "cli.log");
    EXPECT_EQ(run.exit_code, 2) << run.output;
    EXPECT_NE(run.output.find("wavebench run: spec: got '"), std::string::npos) << run.output;
    EXPECT_NE(run.output.find("good"), std::string::npos) << run.output;
    EXPECT_FALSE(fs::exists(dir_ / "runs")) << name;
  }
}

}  // namespace
}  // namespace wavebench::procedures
