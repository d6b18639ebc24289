// Issue #22 item 12, the brake: the in-process simulated brake controller listens on loopback,
// where any local user could reach it. A second Modbus master (another process, the CLI) is
// refused every write without the bench's secret; and a brake energised while the bench is not
// active (forced in process, as a real controller's front panel would) faults the bench with a
// reason that says so, the output commanded off.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <chrono>
#include <cstdlib>
#include <string>
#include <thread>

#include "bench_test_support.hpp"
#include "wavebench/modbus/brake_client.hpp"
#include "wavebench/modbus/modbus_error.hpp"
#include "wavebench/simdevices/powder_brake_controller.hpp"

namespace wavebench::bench {
namespace {

using testing::sim_config;
using testing::SimBench;
namespace reg = simdevices::brake_registers;

modbus::BrakeClientConfig stranger(int port) {
  modbus::BrakeClientConfig c;
  c.link.endpoint.transport = modbus::Transport::tcp;
  c.link.endpoint.host = "127.0.0.1";
  c.link.endpoint.port = port;
  c.link.response_timeout = std::chrono::milliseconds(2000);
  return c;
}

int cli(const std::string& args) {
  const std::string command = std::string(WAVEBENCH_CLI) + " " + args + " >/dev/null 2>&1";
  const int status = std::system(command.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

TEST(HostileBrake, SecondMasterIsRefusedEveryWriteWithoutTheSecret) {
  SimBench sim(sim_config());
  sim.bench->connect();
  sim.bench->idle_for(0.2);
  auto& server = sim.access->brake_server();
  const int port = server.port();
  int tried = 0;

  modbus::BrakeClient client(stranger(port));
  client.connect();
  EXPECT_NO_THROW(client.read());  // reading is harmless and stays open
  EXPECT_THROW(client.set_setpoint(80, modbus::BrakeMode::torque, 0), modbus::ModbusError);
  EXPECT_THROW(client.enable(), modbus::ModbusError);
  EXPECT_THROW(client.set_watchdog(std::chrono::milliseconds(0)), modbus::ModbusError);
  tried += 3;

  // The reproduction of the report: the CLI against the daemon's brake.
  const std::string at = " --modbus tcp:127.0.0.1:" + std::to_string(port);
  EXPECT_NE(cli("brake set 80 --torque" + at), 0);
  EXPECT_NE(cli("brake enable" + at), 0);
  tried += 2;

  // A wrong secret: refused, the connection closed (a guess costs a connection).
  for (const std::uint64_t guess : {0ULL, 1ULL, 0xFFFFFFFFFFFFFFFFULL}) {
    auto wrong = stranger(port);
    wrong.link.unlock_secret = guess;
    modbus::BrakeClient guesser(wrong);
    EXPECT_THROW(guesser.connect(), modbus::ModbusError);
    ++tried;
  }
  EXPECT_GE(server.writes_refused(), 3U);
  EXPECT_EQ(server.wrong_secrets(), 3U);

  sim.bench->idle_for(0.2);
  EXPECT_FALSE(sim.brake_output_on());
  EXPECT_TRUE(sim.brake_setpoint_zero());
  EXPECT_EQ(sim.bench->state(), BenchLifecycle::kInactive) << sim.bench->fault_reason();
  // The secret is not readable back from the unlock registers.
  const bool zeros = server.with_controller([](simdevices::PowderBrakeController& c) {
    for (int i = 0; i < reg::unlock_count; ++i)
      if (c.holding()[static_cast<std::size_t>(reg::unlock + i)] != 0) return false;
    return true;
  });
  EXPECT_TRUE(zeros);
  std::printf("hostile brake: %d writes from a second master tried, all refused\n", tried);
}

TEST(HostileBrake, BrakeEnergisedWhileIdleFaultsTheBench) {
  SimBench sim(sim_config());
  sim.bench->connect();
  sim.bench->idle_for(0.2);
  ASSERT_EQ(sim.bench->state(), BenchLifecycle::kInactive);
  // Forced in process: what a controller's front panel or an unlocked stranger would do.
  sim.access->brake_server().with_controller([](simdevices::PowderBrakeController& c) {
    const std::uint16_t on = reg::control_enable | reg::control_torque_mode;
    c.write_holding(reg::control, 1, &on);
    const std::uint16_t eighty[2] = {0x42A0, 0x0000};  // 80.0f, high word first
    c.write_holding(reg::setpoint, 2, eighty);
  });
  ASSERT_TRUE(sim.brake_output_on());
  const auto start = std::chrono::steady_clock::now();
  const auto deadline = start + std::chrono::seconds(20);
  while (sim.bench->state() != BenchLifecycle::kFault &&
         std::chrono::steady_clock::now() < deadline) {
    try {
      sim.bench->idle_for(0.05);
    } catch (const std::exception&) {
    }
  }
  const auto ms = std::chrono::duration_cast<std::chrono::milliseconds>(
                      std::chrono::steady_clock::now() - start)
                      .count();
  ASSERT_EQ(sim.bench->state(), BenchLifecycle::kFault);
  const std::string reason = sim.bench->fault_reason();
  EXPECT_NE(reason.find("energised while the bench is inactive"), std::string::npos) << reason;
  EXPECT_FALSE(sim.brake_output_on());
  EXPECT_TRUE(sim.brake_setpoint_zero());
  std::printf("hostile brake: energised while idle -> fault after %lld ms: %s\n",
              static_cast<long long>(ms), reason.c_str());
}

}  // namespace
}  // namespace wavebench::bench
