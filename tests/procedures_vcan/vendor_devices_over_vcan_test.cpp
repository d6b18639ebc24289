// Devices as vendors make them, over a real vcan (issue #20): `wavebench simbench` as its own
// process with a servo drive whose TPDO mapping is read-only and laid out unlike the bench's
// default, and which has no heartbeat producer (0x1017 absent: node guarding). The
// commissioning check is green and says so ("used as found", "node guarding"), and a
// 4-position static run completes. Runs in the vcan VM (scripts/vcan-vm/, one test at a time);
// skips where vcan1 is absent. Nothing here asserts on time.
#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <net/if.h>
#include <netinet/in.h>
#include <signal.h>
#include <spawn.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>

#include "simbench_process.hpp"
#include "wavebench/bench/bench_config.hpp"
#include "wavebench/bench/bench_factory.hpp"
#include "wavebench/procedures/run_executor.hpp"
#include "wavebench/storage/run_store.hpp"

namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;
constexpr const char* kInterface = "vcan1";

std::string read_text(const fs::path& p) {
  std::stringstream s;
  s << std::ifstream(p).rdbuf();
  return s.str();
}

void replace(std::string& text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  ASSERT_NE(at, std::string::npos) << "'" << from << "' not in the config";
  text.replace(at, from.size(), to);
}

// The drive's fixed mapping: position before statusword in TPDO1, velocity alone in TPDO2 (no
// following error), unlike the bench's [statusword, position] and [velocity, following error].
constexpr const char* kVendorDrive =
    "    drive: {heartbeat_producer: false,\n"
    "            fixed_tpdo_mapping: {tpdo1: [\"0x6064:0/32\", \"0x6041:0/16\"],\n"
    "                                 tpdo2: [\"0x606C:0/32\"]}}\n";

class VendorDevicesOverVcan : public ::testing::Test {
 protected:
  void SetUp() override {
    if (if_nametoindex(kInterface) == 0)
      GTEST_SKIP() << kInterface << " is absent (runs in the vcan VM)";
    root_ = fs::temp_directory_path() / ("wavebench-vcan-vendor-" + std::to_string(::getpid()));
    fs::remove_all(root_);
    fs::create_directories(root_);
    const fs::path configs = fs::path(WAVEBENCH_SOURCE_DIR) / "configs";

    // The simulated devices: sim.yaml's unit with the vendor-like drive.
    auto devices = read_text(configs / "benches/sim.yaml");
    replace(devices, "../twin/", (configs / "twin").string() + "/");
    for (const char* eds : {"servo_drive.eds", "output_encoder.eds", "torque_sensor.eds"})
      replace(devices, std::string("../eds/") + eds, (configs / "eds" / eds).string());
    replace(devices, "case: sim-true-gear.yaml",
            "case: " + (configs / "benches/sim-true-gear.yaml").string());
    replace(devices, "  simbench:", std::string("  simbench:\n") + kVendorDrive + "   ");
    const auto devices_path = root_ / "devices.yaml";
    std::ofstream(devices_path) << devices;
    const auto error = simbench_.start(kInterface, devices_path.string());
    ASSERT_TRUE(error.empty()) << error;
    port_ = simbench_.port();

    // The bench: vcan-simbench.yaml on this interface and brake port; emulated, so generous
    // times (never a timing assert); the drive guarded every 200 ms, lost after 2 s.
    bench_ = read_text(configs / "benches/vcan-simbench.yaml");
    replace(bench_, "interface: vcan0", std::string("interface: ") + kInterface);
    replace(bench_, "endpoint: \"tcp:127.0.0.1:1502\"",
            "endpoint: \"tcp:127.0.0.1:" + std::to_string(port_) + "\"");
    replace(bench_, "sdo_timeout: \"500 ms\"", "sdo_timeout: \"5 s\"");
    replace(bench_, "cycle_timeout: \"50 ms\"",
            "cycle_timeout: \"1 s\"\n  node_guarding: {guard_time: \"200 ms\", "
            "life_time_factor: 10}");
    replace(bench_, "heartbeat_timeout: \"500 ms\"", "heartbeat_timeout: \"5 s\"");
    // The fixed mapping carries no following error (0x60F4): its limit cannot be judged, and a
    // config that asks for it is refused at connect (a user leaves it out for such a drive).
    replace(bench_, "  max_following_error: \"2 rev\"\n", "");
    replace(bench_, "../twin/", (configs / "twin").string() + "/");
    for (const char* eds : {"servo_drive.eds", "output_encoder.eds", "torque_sensor.eds"})
      replace(bench_, std::string("../eds/") + eds, (configs / "eds" / eds).string());
    bench_path_ = root_ / "bench.yaml";
    std::ofstream(bench_path_) << bench_;
  }
  void TearDown() override { fs::remove_all(root_); }

  fs::path root_;
  std::string bench_;
  fs::path bench_path_;
  wavebench::testing::SimbenchProcess simbench_;
  int port_ = -1;
};

TEST_F(VendorDevicesOverVcan, CheckGreenAndFourPositionStaticRunComplete) {
  using namespace wavebench;
  const std::string command = std::string(WAVEBENCH_BINARY_DIR) +
                              "/src/cli/wavebench bench check " + bench_path_.string() + " 2>&1";
  FILE* pipe = ::popen(command.c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  std::string output;
  std::array<char, 4096> buffer{};
  while (std::fgets(buffer.data(), buffer.size(), pipe)) output += buffer.data();
  const int status = ::pclose(pipe);
  std::printf("%s", output.c_str());
  ASSERT_TRUE(WIFEXITED(status)) << output;
  EXPECT_EQ(WEXITSTATUS(status), 0) << output;
  EXPECT_EQ(output.find("RED"), std::string::npos) << output;
  EXPECT_NE(output.find("used as found"), std::string::npos) << output;
  EXPECT_NE(output.find("node guarding"), std::string::npos) << output;

  storage::RunStore store(root_ / "runs", "test");
  auto config = bench::load_bench_config(bench_path_);
  auto bench = bench::make_bench(config);
  ASSERT_EQ(bench::simulated_access(*bench), nullptr) << "must not be the in-process bench";
  bench->connect();
  procedures::RunRequest request;
  request.procedure = "static";
  request.options = {{"positions", 4},        {"loads_nm", {0}},
                     {"window_s", 0.2},       {"move_speed_rad_s", 200.0},
                     {"brake_settle_s", 0.2}, {"calibrate_twin", false}};
  request.config_text = config.text;
  request.twin = false;
  request.report = false;
  const auto out = procedures::execute_run(*bench, store, request);
  ASSERT_EQ(out.status, storage::RunStatus::kComplete) << out.reason;
  ASSERT_EQ(out.results.at("static").size(), 2U);  // both directions at 0 N*m
  for (const auto& pass : out.results.at("static")) EXPECT_EQ(pass.at("points").size(), 4U);
  bench->disconnect();
}

}  // namespace
