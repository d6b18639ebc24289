// `wavebench can ...` against the simulated bench's nodes on a real vcan0: the commissioning
// commands as an operator runs them, as child processes.
#include <gtest/gtest.h>
#include <unistd.h>

#include "../support/simulated_devices_gear.hpp"
#include "vcan_support.hpp"
#include "wavebench/can/socket_can_bus.hpp"
#include "wavebench/simdevices/simulated_bench.hpp"

namespace wavebench::can {
namespace {

using testing::kVcan;
using testing::run_until;

struct CliResult {
  int status;
  std::string output;
};

class VcanCli : public ::testing::Test {
 protected:
  void SetUp() override {
    WAVEBENCH_REQUIRE_VCAN();
    ASSERT_EQ(::access(cli.c_str(), X_OK), 0) << cli << " is not built";
    devices = std::make_unique<SocketCanBus>(io, kVcan);
    simdevices::SimulatedBenchConfig config = wavebench::testing::simulated_devices_config();
    config.clock = simdevices::BenchClock::kSyncDriven;  // time moves only with SYNC
    bench = std::make_unique<simdevices::SimulatedBench>(config, *devices);
    bench->start();
  }
  // Runs the CLI while this process keeps serving the simulated nodes.
  CliResult wavebench(std::vector<std::string> args) {
    args.insert(args.begin(), {cli, "can"});
    const std::string log =
        "/tmp/wavebench_cli_" + std::to_string(::getpid()) + "_" + std::to_string(++runs) + ".log";
    testing::ChildProcess child(args, log);
    EXPECT_TRUE(run_until(
        io, [&] { return child.exited(); }, std::chrono::seconds(300)));
    CliResult r{child.wait(), child.output()};
    std::remove(log.c_str());
    return r;
  }

  const std::string cli = WAVEBENCH_BINARY_DIR "/src/cli/wavebench";
  boost::asio::io_context io;
  std::unique_ptr<SocketCanBus> devices;
  std::unique_ptr<simdevices::SimulatedBench> bench;
  int runs = 0;
};

TEST_F(VcanCli, ScanListsNodesWithDeviceTypeAndIdentity) {
  const auto r = wavebench({"scan", kVcan, "--timeout", "3000"});
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("   1  0x00020192  0x00000A57  0x00000402"), std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("   3  0x00020196"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("\n   4  "), std::string::npos) << r.output;
}

TEST_F(VcanCli, SdoReadWriteAndAbortText) {
  auto r = wavebench({"sdo-read", kVcan, "1", "0x1008", "0", "--type", "str"});
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(r.output, "WB-SIM servo drive\n");
  r = wavebench({"sdo-write", kVcan, "1", "0x1017", "0", "u16", "4000"});
  EXPECT_EQ(r.status, 0) << r.output;
  r = wavebench({"sdo-read", kVcan, "1", "0x1017", "0", "--type", "u16"});
  EXPECT_EQ(r.output, "4000\n");
  r = wavebench({"sdo-read", kVcan, "1", "0x1000", "0"});
  EXPECT_EQ(r.output, "0x00020192 (131474) [92 01 02 00]\n");
  r = wavebench({"sdo-read", kVcan, "1", "0x2345", "0"});
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.output.find("06020000 object does not exist in the object dictionary"),
            std::string::npos)
      << r.output;
  r = wavebench({"sdo-write", kVcan, "1", "0x1017", "0", "u8", "300"});
  EXPECT_EQ(r.status, 2) << "bad input never reaches the bus: " << r.output;
}

TEST_F(VcanCli, NmtAndDump) {
  const int receivers = testing::registered_receivers();
  const std::string log = "/tmp/wavebench_cli_dump_" + std::to_string(::getpid()) + ".log";
  testing::ChildProcess dump({cli, "can", "dump", kVcan}, log);
  ASSERT_TRUE(
      run_until(io, [&] { return testing::registered_receivers() > receivers || dump.exited(); }));
  auto r = wavebench({"nmt", kVcan, "start", "0"});
  EXPECT_EQ(r.status, 0) << r.output;
  ASSERT_TRUE(run_until(
      io, [&] { return bench->drive().nmt_state() == simdevices::NmtState::kOperational; }));
  SocketCanBus master(io, kVcan);
  master.send(Frame::make(0x080, {}));
  // The dump flushes every line: once the SYNC line is there, stop it as an operator would.
  ASSERT_TRUE(run_until(io, [&] { return dump.output().find("080#  SYNC") != std::string::npos; }))
      << dump.output();
  EXPECT_EQ(dump.stop(SIGINT), 0);
  const auto out = dump.output();
  EXPECT_NE(out.find("000#0100  NMT start all nodes"), std::string::npos) << out;
  EXPECT_NE(out.find("080#  SYNC"), std::string::npos) << out;
  std::remove(log.c_str());
}

}  // namespace
}  // namespace wavebench::can
