// `wavebench bench check CONFIG` as a process on the in-process simulated bench: exit 0 and all
// rows green as shipped; a wrong node id, an object missing from the EDS, a wrong identity, an
// EDS describing another device and an unreachable brake: a red row naming each and exit 1; a bad
// config: exit 2. A drive without the CiA-optional 0x603F and 0x1018:4 is green and runs.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

namespace {

namespace fs = std::filesystem;

struct CommandResult {
  int exit_code = -1;
  std::string output;
};

// `stderr_too`: the output is stdout and stderr; otherwise stdout alone (stderr discarded).
CommandResult run_wavebench(const std::string& args, bool stderr_too = true) {
  const std::string command = std::string(WAVEBENCH_BINARY_DIR) + "/src/cli/wavebench " + args +
                              (stderr_too ? " 2>&1" : " 2>/dev/null");
  CommandResult result;
  FILE* pipe = ::popen(command.c_str(), "r");
  if (!pipe) return result;
  std::array<char, 4096> buffer{};
  while (std::fgets(buffer.data(), buffer.size(), pipe)) result.output += buffer.data();
  const int status = ::pclose(pipe);
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

std::string read(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

void replace(std::string& text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  ASSERT_NE(at, std::string::npos) << "'" << from << "' not in the config";
  text.replace(at, from.size(), to);
}

class BenchCheckCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("wavebench-bench-check-" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    const fs::path configs = fs::path(WAVEBENCH_SOURCE_DIR) / "configs";
    // sim.yaml with its relative paths made absolute, so variants can live in a temp folder.
    sim_ = read(configs / "benches/sim.yaml");
    replace(sim_, "../twin/", (configs / "twin").string() + "/");
    replace(sim_, "../eds/servo_drive.eds", (configs / "eds/servo_drive.eds").string());
    replace(sim_, "../eds/output_encoder.eds", (configs / "eds/output_encoder.eds").string());
    replace(sim_, "../eds/torque_sensor.eds", (configs / "eds/torque_sensor.eds").string());
    replace(sim_, "case: sim-true-gear.yaml",
            "case: " + (configs / "benches/sim-true-gear.yaml").string());
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string write(const std::string& name, const std::string& text) {
    const auto path = dir_ / name;
    std::ofstream(path) << text;
    return path.string();
  }
  CommandResult check(const std::string& name, const std::string& text) {
    return run_wavebench("bench check " + write(name, text));
  }

  fs::path dir_;
  std::string sim_;
};

bool has_red_row(const std::string& output, const std::string& device, const std::string& item) {
  std::istringstream lines(output);
  std::string line;
  while (std::getline(lines, line))
    if (line.rfind("RED", 0) == 0 && line.find(device) != std::string::npos &&
        line.find(item) != std::string::npos)
      return true;
  return false;
}

TEST_F(BenchCheckCli, AllGreenOnTheSimulatedBench) {
  const auto r = check("sim.yaml", sim_);
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("all "), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("checks green"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("RED"), std::string::npos) << r.output;

  const auto json = run_wavebench("bench check --json " + write("sim-json.yaml", sim_));
  EXPECT_EQ(json.exit_code, 0) << json.output;
  const auto j = nlohmann::json::parse(json.output);
  EXPECT_TRUE(j["all_green"].get<bool>());
  EXPECT_GT(j["rows"].size(), 30u);
}

TEST_F(BenchCheckCli, WrongNodeIdGivesARedRowAndExit1) {
  auto text = sim_;
  replace(text, "nodes: {drive: 1,", "nodes: {drive: 5,");
  replace(text, "  simbench:", "  simbench:\n    drive: {node_id: 1}\n   ");
  const auto r = check("wrong-node.yaml", text);
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_TRUE(has_red_row(r.output, "servo drive (node 5)", "node answers")) << r.output;
}

TEST_F(BenchCheckCli, ObjectMissingFromTheEdsGivesARedRowAndExit1) {
  auto eds = read(fs::path(WAVEBENCH_SOURCE_DIR) / "configs/eds/servo_drive.eds");
  const auto at = eds.find("[6081]");
  ASSERT_NE(at, std::string::npos);
  eds.erase(at, eds.find("\n\n", at) + 2 - at);
  replace(eds, "=0x6081\n", "=0x6080\n");
  const auto eds_path = write("no6081.eds", eds);
  auto text = sim_;
  replace(text, (fs::path(WAVEBENCH_SOURCE_DIR) / "configs/eds/servo_drive.eds").string(),
          eds_path);
  const auto r = check("missing-object.yaml", text);
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_TRUE(has_red_row(r.output, "servo drive", "0x6081:0 profile velocity: not in the EDS"))
      << r.output;
}

TEST_F(BenchCheckCli, WrongIdentityGivesARedRowAndExit1) {
  auto text = sim_;
  replace(text, "identity: {vendor_id: 0x00000A57, product_code: 0x00000402}",
          "identity: {vendor_id: 0x999, product_code: 0x00000402}");
  const auto r = check("wrong-identity.yaml", text);
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_TRUE(
      has_red_row(r.output, "servo drive", "expected 0x00000999 (drive.identity.vendor_id)"))
      << r.output;
}

TEST_F(BenchCheckCli, UnreachableBrakeGivesARedRowAndExit1) {
  auto text = sim_;
  replace(text, "\nsimulated:\n", "\nsimulated:\n  brake_server: false\n");
  replace(text, "\nbrake:", "\nbrake:\n  link: {endpoint: \"tcp:127.0.0.1:1\", unit_id: 1}\n ");
  const auto r = check("no-brake.yaml", text);
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_TRUE(has_red_row(r.output, "brake controller (tcp:127.0.0.1:1)", "registers readable"))
      << r.output;
}

TEST_F(BenchCheckCli, BadConfigExits2NamingTheKey) {
  auto text = sim_;
  replace(text, (fs::path(WAVEBENCH_SOURCE_DIR) / "configs/eds/servo_drive.eds").string(),
          (dir_ / "absent.eds").string());
  const auto r = check("bad.yaml", text);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("drive.eds"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("absent.eds"), std::string::npos) << r.output;
}

bool has_green_row(const std::string& output, const std::string& device, const std::string& item) {
  std::istringstream lines(output);
  std::string line;
  while (std::getline(lines, line))
    if (line.rfind("ok", 0) == 0 && line.find(device) != std::string::npos &&
        line.find(item) != std::string::npos)
      return true;
  return false;
}

TEST_F(BenchCheckCli, JsonIsAloneOnStdoutWhenConnectWarns) {
  // A bus-load warning threshold below the bench's load: connect warns, the row is red.
  auto text = sim_;
  replace(text, "bus_load_warning: 0.8", "bus_load_warning: 0.01");
  const auto r = run_wavebench("bench check --json " + write("warn.yaml", text), false);
  EXPECT_EQ(r.exit_code, 1) << r.output;
  nlohmann::json j;
  ASSERT_NO_THROW(j = nlohmann::json::parse(r.output)) << r.output;
  EXPECT_FALSE(j["all_green"].get<bool>());
  const auto both = run_wavebench("bench check --json " + write("warn2.yaml", text), true);
  EXPECT_NE(both.output.find("bus load"), std::string::npos) << both.output;
}

TEST_F(BenchCheckCli, DriveWithoutErrorCodeAndSerialNumberIsGreenAndRuns) {
  auto text = sim_;
  replace(text, "  simbench:",
          "  simbench:\n    drive: {absent_objects: [\"0x603F\", \"0x1018:4\"]}\n   ");
  const auto file = write("no603f.yaml", text);
  const auto r = run_wavebench("bench check " + file);
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(has_green_row(r.output, "servo drive", "0x603F:0 error code")) << r.output;
  EXPECT_NE(r.output.find("absent (optional): a fault is reported"), std::string::npos) << r.output;
  EXPECT_TRUE(has_green_row(r.output, "servo drive", "0x1018:4 serial number")) << r.output;
  EXPECT_NE(r.output.find("0x1018:4 serial absent (optional)"), std::string::npos) << r.output;

  const auto out = dir_ / "runs";
  const auto run = run_wavebench("run static --bench " + file +
                                 " --positions 4 --loads 0 --quiet --out " + out.string());
  EXPECT_EQ(run.exit_code, 0) << run.output;
}

TEST_F(BenchCheckCli, EdsOfAnotherDeviceGivesARedIdentityRowNamingBoth) {
  auto eds = read(fs::path(WAVEBENCH_SOURCE_DIR) / "configs/eds/servo_drive.eds");
  replace(eds, "VendorNumber=0x00000A57", "VendorNumber=0x000000FB");
  replace(eds, "ProductNumber=0x00000402", "ProductNumber=0x60500000");
  const auto eds_path = write("other-vendor.eds", eds);
  auto text = sim_;
  replace(text, (fs::path(WAVEBENCH_SOURCE_DIR) / "configs/eds/servo_drive.eds").string(),
          eds_path);
  // The config expects nothing itself: only the EDS says who the device should be.
  replace(text, "identity: {vendor_id: 0x00000A57, product_code: 0x00000402}", "identity: {}");
  const auto r = check("other-vendor.yaml", text);
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_TRUE(has_red_row(r.output, "servo drive", "identity")) << r.output;
  EXPECT_NE(r.output.find("device vendor-ID 0x00000A57, the EDS VendorNumber says 0x000000FB"),
            std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("device product code 0x00000402, the EDS ProductNumber says 0x60500000"),
            std::string::npos)
      << r.output;
}

// Issue #20: a drive in rpm under a config in counts/s. Stating its unit (0x60A9) it is a red
// units row by itself; without 0x60A9, --motion finds it by a short bounded motion.
TEST_F(BenchCheckCli, DriveInRpmUnderACountsConfigIsRedByItsSiUnitOrByMotion) {
  auto stating = sim_;
  replace(stating, "  simbench:",
          "  simbench:\n    drive: {velocity_unit: rpm, si_unit_objects: true}\n   ");
  auto r = check("rpm-stating.yaml", stating);
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_TRUE(has_red_row(r.output, "servo drive", "the drive says 0x60A9 = 0x00B44700 (rev/min)"))
      << r.output;

  auto silent = sim_;
  replace(silent, "  simbench:", "  simbench:\n    drive: {velocity_unit: rpm}\n   ");
  r = run_wavebench("bench check --motion " + write("rpm-silent.yaml", silent));
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_TRUE(has_red_row(r.output, "servo drive", "the drive's velocity unit is likely rpm"))
      << r.output;
  // The motion is the check's default; --no-motion keeps the bench still and says so.
  r = run_wavebench("bench check " + write("rpm-default.yaml", silent));
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_TRUE(has_red_row(r.output, "servo drive", "the drive's velocity unit is likely rpm"))
      << r.output;
  r = run_wavebench("bench check --no-motion " + write("rpm-still.yaml", silent));
  EXPECT_NE(r.output.find("not compared by motion"), std::string::npos) << r.output;

  r = run_wavebench("bench check --motion " + write("sim-motion.yaml", sim_));
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("the units agree"), std::string::npos) << r.output;
}

}  // namespace
