// `wavebench simbench` as its own process on vcan1, talked to across real SocketCAN sockets by
// the project's master and by python-can as an independent peer. Runs inside the vcan VM
// (scripts/vcan-vm/); skips where vcan1 is absent.
#include <gtest/gtest.h>
#include <net/if.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>

#include <array>
#include <boost/asio/io_context.hpp>
#include <chrono>
#include <cstdio>
#include <memory>
#include <set>
#include <string>

#include "wavebench/can/socket_can_bus.hpp"
#include "wavebench/canopen/cia402_drive.hpp"
#include "wavebench/canopen/sdo_client.hpp"

extern char** environ;

namespace {

using namespace std::chrono_literals;
constexpr const char* kInterface = "vcan1";

class SimbenchProcess : public ::testing::Test {
 protected:
  void SetUp() override {
    if (if_nametoindex(kInterface) == 0)
      GTEST_SKIP() << kInterface << " is absent (runs in the vcan VM)";
    bus = std::make_unique<wavebench::can::SocketCanBus>(io, kInterface);
    sub = bus->on_frame([this](const wavebench::can::Frame& f) {
      if (f.id >= 0x701 && f.id <= 0x77F && f.len == 1 && f.data[0] == 0x00) booted.insert(f.id);
    });
    const std::string exe = std::string(WAVEBENCH_BINARY_DIR) + "/src/cli/wavebench";
    std::array<std::string, 6> args{exe, "simbench", "--can", kInterface, "--duration", "120"};
    std::array<char*, 7> argv{};
    for (std::size_t i = 0; i < args.size(); ++i) argv[i] = args[i].data();
    ASSERT_EQ(posix_spawn(&pid, exe.c_str(), nullptr, nullptr, argv.data(), environ), 0) << exe;
    const auto deadline = std::chrono::steady_clock::now() + 60s;  // slow under emulation
    while (booted.size() < 3 && std::chrono::steady_clock::now() < deadline) io.run_for(50ms);
    io.restart();
  }
  void TearDown() override {
    if (pid > 0) {
      kill(pid, SIGTERM);
      int status = 0;
      waitpid(pid, &status, 0);
    }
  }

  boost::asio::io_context io;
  std::unique_ptr<wavebench::can::SocketCanBus> bus;
  wavebench::can::CanBus::Subscription sub;
  std::set<std::uint32_t> booted;
  pid_t pid = -1;
};

TEST_F(SimbenchProcess, BootsThreeNodesAndServesTheMaster) {
  ASSERT_EQ(booted, (std::set<std::uint32_t>{0x701, 0x703, 0x704}));
  wavebench::canopen::SdoClient sdo(*bus, 1, 10000ms);  // generous: emulated, loaded
  const auto name = sdo.upload(0x1008, 0);
  EXPECT_EQ(std::string(name.begin(), name.end()), "WB-SIM servo drive");
  wavebench::canopen::Cia402Drive drive(sdo, {.state_timeout = 10000ms});
  drive.enable_operation();
  drive.set_mode(wavebench::canopen::OperationMode::profile_position);
  wavebench::canopen::ProfileMove move;
  move.target = 131072;
  drive.move(move);
  drive.wait_target_reached(30000ms);
  EXPECT_NEAR(sdo.read<std::int32_t>(0x6064, 0), move.target, 20);
}

TEST_F(SimbenchProcess, PythonCanPeerReadsTheEncoderDeviceType) {
  ASSERT_EQ(booted.size(), 3u);
  const std::string script =
      "import can\n"
      "bus = can.interface.Bus(channel='vcan1', interface='socketcan')\n"
      "bus.send(can.Message(arbitration_id=0x603, is_extended_id=False,"
      " data=[0x40, 0x00, 0x10, 0, 0, 0, 0, 0]))\n"
      "while True:\n"
      "    m = bus.recv(30)\n"
      "    if m is None: print('timeout'); break\n"
      "    if m.arbitration_id == 0x583: print(m.data.hex()); break\n";
  const std::string cmd = "/usr/bin/python3 -c \"" + script + "\"";
  FILE* p = popen(cmd.c_str(), "r");
  ASSERT_NE(p, nullptr);
  char line[128] = {};
  const bool got = std::fgets(line, sizeof line, p) != nullptr;
  pclose(p);
  ASSERT_TRUE(got);
  EXPECT_EQ(std::string(line), "4300100096010200\n");
}

}  // namespace
