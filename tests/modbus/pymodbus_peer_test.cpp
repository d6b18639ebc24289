// A pymodbus server (an independent Modbus implementation) with the default map serves the
// project's client.
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>

#include "brake_test_support.hpp"
#include "peer_process.hpp"

namespace wavebench::testing {
namespace {

int free_loopback_port() {
  const int s = socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  bind(s, reinterpret_cast<sockaddr*>(&a), sizeof a);
  socklen_t len = sizeof a;
  getsockname(s, reinterpret_cast<sockaddr*>(&a), &len);
  ::close(s);
  return ntohs(a.sin_port);
}

TEST(PymodbusPeer, ServesTheClient) {
  int st = 0;
  run_command("/usr/bin/python3 -c 'import pymodbus.server'", st);
  if (st != 0) GTEST_SKIP() << "python3-pymodbus not installed";
  const int port = free_loopback_port();
  BackgroundProcess server({"/usr/bin/python3", WAVEBENCH_PYMODBUS_SERVER, std::to_string(port)});
  ASSERT_TRUE(server.started());
  modbus::BrakeClient client(client_config_tcp(port));
  modbus::BrakeReadback r;
  ASSERT_TRUE(eventually(
      [&] {
        try {
          r = client.read();
          return true;
        } catch (const modbus::ModbusError&) {
          return false;
        }
      },
      20s));
  EXPECT_TRUE(r.status.output_on);
  EXPECT_TRUE(r.status.alarm);
  EXPECT_TRUE(r.status.over_temperature);
  EXPECT_TRUE(r.status.at_setpoint);
  EXPECT_DOUBLE_EQ(r.coil_current_a, 1.25);
  EXPECT_DOUBLE_EQ(r.torque_nm, 62.5);
  EXPECT_DOUBLE_EQ(r.temperature_c, 81.5);
  EXPECT_DOUBLE_EQ(r.slip_power_w, 12.0);
  EXPECT_EQ(r.alarm_code, 1);
  EXPECT_NE(r.alarm_text.find("coil over-temperature"), std::string::npos) << r.alarm_text;

  client.set_setpoint(30.0, modbus::BrakeMode::torque, 7.5);
  client.enable();
  client.set_watchdog(400ms);
  client.heartbeat();
  client.heartbeat();
  // Read the holding registers back through the pymodbus store.
  modbus::ModbusLink link(client_config_tcp(port).link);
  link.connect();
  const auto h = link.read_registers(modbus::RegisterTable::holding, 0, 14);
  EXPECT_EQ(h[0], 0b101);  // enable + torque mode
  EXPECT_EQ(h[1], 400);
  EXPECT_EQ(h[2], 2);
  EXPECT_EQ(h[10], 0x41F0);  // 30.0f
  EXPECT_EQ(h[11], 0x0000);
  EXPECT_EQ(h[12], 0x40F0);  // 7.5f
  EXPECT_EQ(h[13], 0x0000);
}

}  // namespace
}  // namespace wavebench::testing
