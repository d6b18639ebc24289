// A static TE test with 4 positions, run by the bench code (CANopen master + Modbus brake
// client) against `wavebench simbench` as its own process on vcan1 with its brake on Modbus TCP,
// and the same test on the in-process simulated bench: both complete and agree. Runs in the
// vcan VM (scripts/vcan-vm/); skips where vcan1 is absent. Nothing here asserts on time.
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
#include "wavebench/storage/sample_log.hpp"

namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;
constexpr const char* kInterface = "vcan1";

wavebench::procedures::RunRequest four_position_static(const std::string& config_text) {
  wavebench::procedures::RunRequest request;
  request.procedure = "static";
  // Faster moves and shorter windows than the defaults: under emulation each SYNC cycle
  // crosses two processes, so bench time is what the test costs.
  request.options = {{"positions", 4},        {"loads_nm", {0, 60}},
                     {"window_s", 0.2},       {"move_speed_rad_s", 200.0},
                     {"brake_settle_s", 0.2}, {"calibrate_twin", false}};
  request.config_text = config_text;
  request.twin = false;  // the comparison is of the measurement; the twin has its own tests
  request.report = false;
  return request;
}

const nlohmann::json* find_pass(const nlohmann::json& results, const std::string& direction,
                                double load) {
  for (const auto& pass : results.at("static"))
    if (pass.at("direction") == direction &&
        std::abs(pass.at("load_nm").get<double>() - load) < 1e-9)
      return &pass;
  return nullptr;
}

class StaticOverVcan : public ::testing::Test {
 protected:
  void SetUp() override {
    if (if_nametoindex(kInterface) == 0)
      GTEST_SKIP() << kInterface << " is absent (runs in the vcan VM)";
    root_ = fs::temp_directory_path() / ("wavebench-vcan-static-" + std::to_string(::getpid()));
    fs::remove_all(root_);
    const std::string config = std::string(WAVEBENCH_SOURCE_DIR) + "/configs/benches/sim.yaml";
    const auto error = simbench_.start(kInterface, config);
    ASSERT_TRUE(error.empty()) << error;
    port_ = simbench_.port();
  }
  void TearDown() override { fs::remove_all(root_); }

  fs::path root_;
  wavebench::testing::SimbenchProcess simbench_;
  int port_ = -1;
};

TEST_F(StaticOverVcan, FourPositionsCompleteAndAgreeWithTheInProcessBench) {
  using namespace wavebench;
  const fs::path config_path = fs::path(WAVEBENCH_SOURCE_DIR) / "configs/benches/sim.yaml";

  // Across processes: the master on vcan1, the brake client on Modbus TCP.
  auto over_vcan_config = bench::load_bench_config(config_path);
  over_vcan_config.can.interface = kInterface;
  over_vcan_config.can.sdo_timeout_s = 5;    // emulated: generous, never a timing assert
  over_vcan_config.can.cycle_timeout_s = 1;  // a cycle's PDOs across processes under TCG
  over_vcan_config.brake.link.endpoint.transport = modbus::Transport::tcp;
  over_vcan_config.brake.link.endpoint.host = "127.0.0.1";
  over_vcan_config.brake.link.endpoint.port = port_;
  nlohmann::json over_vcan;
  std::uint64_t vcan_samples = 0;
  {
    storage::RunStore store(root_ / "vcan", "test");
    auto bench = bench::make_bench(over_vcan_config);
    ASSERT_EQ(bench::simulated_access(*bench), nullptr) << "must not be the in-process bench";
    bench->connect();
    const auto out = procedures::execute_run(*bench, store, four_position_static(over_vcan_config.text));
    ASSERT_EQ(out.status, storage::RunStatus::kComplete) << out.reason;
    over_vcan = out.results;
    const auto log = storage::read_sample_log(store.paths(out.run_id).samples);
    vcan_samples = log.samples.size();
    EXPECT_FALSE(log.corrupt_record);
    bench->disconnect();
  }

  // In-process: the same simulated unit and the same procedure.
  nlohmann::json in_process;
  {
    storage::RunStore store(root_ / "inproc", "test");
    auto config = bench::load_bench_config(config_path);
    auto bench = bench::make_bench(config);
    ASSERT_NE(bench::simulated_access(*bench), nullptr);
    bench->connect();
    const auto out = procedures::execute_run(*bench, store, four_position_static(config.text));
    ASSERT_EQ(out.status, storage::RunStatus::kComplete) << out.reason;
    in_process = out.results;
    bench->disconnect();
  }

  EXPECT_GT(vcan_samples, 1000U);
  ASSERT_EQ(over_vcan.at("static").size(), 4U);  // 2 directions x 2 loads
  for (const char* direction : {"forward", "reverse"}) {
    for (double load : {0.0, 60.0}) {
      SCOPED_TRACE(std::string(direction) + " at " + std::to_string(load) + " N*m");
      const auto* a = find_pass(over_vcan, direction, load);
      const auto* b = find_pass(in_process, direction, load);
      ASSERT_NE(a, nullptr);
      ASSERT_NE(b, nullptr);
      EXPECT_EQ(a->at("points").size(), 4U);
      // The two benches are the same unit, sampled by different schedules of SYNC across
      // processes: agreement to the acceptance tolerance of the static test (0.1 arcmin).
      for (const char* key : {"mean_arcmin", "p2p_arcmin", "std_arcmin"}) {
        EXPECT_NEAR(a->at(key).get<double>(), b->at(key).get<double>(), 0.1) << key;
        std::printf("%s %4.0f N*m %-12s vcan %+8.4f  in-process %+8.4f arcmin\n", direction, load,
                    key, a->at(key).get<double>(), b->at(key).get<double>());
      }
    }
  }
}

// `wavebench bench check` as its own process against the same simbench process (issue #9):
// vcan-simbench.yaml on this test's interface and brake port, every row green.
using BenchCheckOverVcan = StaticOverVcan;

TEST_F(BenchCheckOverVcan, AllGreenAgainstSimbenchAsItsOwnProcess) {
  const fs::path configs = fs::path(WAVEBENCH_SOURCE_DIR) / "configs";
  std::stringstream text;
  text << std::ifstream(configs / "benches/vcan-simbench.yaml").rdbuf();
  std::string config = text.str();
  const auto replace = [&config](const std::string& from, const std::string& to) {
    const auto at = config.find(from);
    ASSERT_NE(at, std::string::npos) << from;
    config.replace(at, from.size(), to);
  };
  replace("interface: vcan0", std::string("interface: ") + kInterface);
  replace("endpoint: \"tcp:127.0.0.1:1502\"",
          "endpoint: \"tcp:127.0.0.1:" + std::to_string(port_) + "\"");
  replace("sdo_timeout: \"500 ms\"", "sdo_timeout: \"5 s\"");  // emulated: generous
  replace("cycle_timeout: \"50 ms\"", "cycle_timeout: \"1 s\"");
  replace("../twin/", (configs / "twin").string() + "/");
  for (const char* eds : {"servo_drive.eds", "output_encoder.eds", "torque_sensor.eds"})
    replace(std::string("../eds/") + eds, (configs / "eds" / eds).string());
  fs::create_directories(root_);
  const auto path = root_ / "vcan-check.yaml";
  std::ofstream(path) << config;

  const std::string command = std::string(WAVEBENCH_BINARY_DIR) +
                              "/src/cli/wavebench bench check " + path.string() + " 2>&1";
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
  EXPECT_NE(output.find("checks green"), std::string::npos) << output;
}

}  // namespace
