#include <gtest/gtest.h>

#include "brake_test_support.hpp"

namespace wavebench::testing {
namespace {

using modbus::BrakeClient;
using modbus::BrakeMode;
using modbus::ModbusError;
using modbus::ModbusErrorKind;

// The simulated controller on the master side of a pty, the client on the slave side as if it
// were a serial port.
class BrakeClientRtu : public ::testing::Test {
 protected:
  BrakeClientRtu() {
    simdevices::BrakeServerOptions o;
    o.endpoint = modbus::parse_modbus_endpoint("rtu:" + pty.slave_path() + ":115200");
    o.rtu_fd = pty.release_master();
    o.real_time = false;
    server = simdevices::start_brake_server(o);
    auto c = client_config_tcp(0);
    c.link.endpoint = modbus::parse_modbus_endpoint("rtu:" + pty.slave_path() + ":115200");
    client = std::make_unique<BrakeClient>(c);
  }
  simdevices::PtyPair pty;
  std::unique_ptr<simdevices::BrakeServer> server;
  std::unique_ptr<BrakeClient> client;
};

TEST_F(BrakeClientRtu, SetpointRampAndReadback) {
  client->connect();
  client->set_setpoint(1.6, BrakeMode::current, 0.8);
  client->enable();
  server->step(1.0);
  auto r = client->read();
  EXPECT_TRUE(r.status.output_on);
  EXPECT_NEAR(r.coil_current_a, 0.8, 1e-5);
  server->step(1.0);
  server->step(5.0);
  r = client->read();
  EXPECT_NEAR(r.coil_current_a, 1.6, 1e-5);
  EXPECT_NEAR(r.torque_nm, 80.0, 1e-3);
  EXPECT_TRUE(r.status.at_setpoint);
}

TEST_F(BrakeClientRtu, WatchdogTripAndAlarmReset) {
  client->set_watchdog(200ms);
  client->set_setpoint(1.0, BrakeMode::current, 0.0);
  client->enable();
  for (int i = 0; i < 5; ++i) {
    server->step(0.1);
    client->heartbeat();
  }
  EXPECT_FALSE(client->read().status.watchdog_tripped);
  server->step(0.25);  // heartbeats stopped
  auto r = client->read();
  EXPECT_TRUE(r.status.watchdog_tripped);
  EXPECT_TRUE(r.status.alarm);
  EXPECT_FALSE(r.status.output_on);
  EXPECT_EQ(r.alarm_code, 2);
  client->reset_alarm();
  client->heartbeat();
  r = client->read();
  EXPECT_FALSE(r.status.alarm);
  EXPECT_EQ(r.alarm_text, "no alarm");
}

TEST_F(BrakeClientRtu, FaultsGiveClearErrorsAndTheLinkRecovers) {
  client->connect();
  using K = simdevices::BrakeFaultKind;
  const struct {
    K kind;
    ModbusErrorKind expected;
  } cases[] = {{K::exception_response, ModbusErrorKind::exception},
               {K::wrong_unit_id, ModbusErrorKind::wrong_unit},
               {K::garbage_bytes, ModbusErrorKind::bad_reply},
               {K::dropped_connection, ModbusErrorKind::timeout},
               {K::delayed_reply, ModbusErrorKind::timeout}};
  for (const auto& c : cases) {
    simdevices::BrakeFault f;
    f.kind = c.kind;
    f.delay = 2500ms;
    f.requests = 1;
    server->inject_fault(f);
    try {
      client->read();
      ADD_FAILURE() << "no error for fault " << static_cast<int>(c.kind);
    } catch (const ModbusError& e) {
      EXPECT_EQ(e.kind(), c.expected) << e.what();
    }
    // The late reply of a delayed fault must not be taken for the next answer.
    ASSERT_TRUE(eventually([&] {
      try {
        return client->read().temperature_c == 25.0;
      } catch (const ModbusError&) {
        return false;
      }
    })) << static_cast<int>(c.kind);
  }
}

}  // namespace
}  // namespace wavebench::testing
