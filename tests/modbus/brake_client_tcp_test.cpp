#include <gtest/gtest.h>

#include <atomic>
#include <mutex>
#include <vector>

#include "brake_test_support.hpp"
#include "wavebench/modbus/brake_supervisor.hpp"

namespace wavebench::testing {
namespace {

using modbus::BrakeClient;
using modbus::BrakeMode;

class BrakeClientTcp : public ::testing::Test {
 protected:
  std::unique_ptr<simdevices::BrakeServer> server = start_tcp_brake();
  BrakeClient client{client_config_tcp(server->port())};
};

TEST_F(BrakeClientTcp, SetpointAndReadback) {
  ASSERT_GT(server->port(), 0);
  client.connect();
  client.set_setpoint(1.2, BrakeMode::current, 0.0);
  client.enable();
  server->step(5.0);
  const auto r = client.read();
  EXPECT_TRUE(r.status.output_on);
  EXPECT_TRUE(r.status.at_setpoint);
  EXPECT_FALSE(r.status.alarm);
  EXPECT_NEAR(r.coil_current_a, 1.2, 1e-6);
  EXPECT_NEAR(r.torque_nm, 60.0, 1e-3);
  EXPECT_NEAR(r.temperature_c, 25.0, 1e-6);
  EXPECT_EQ(r.slip_power_w, 0.0);
  EXPECT_EQ(r.alarm_code, 0);
  EXPECT_EQ(r.alarm_text, "no alarm");

  server->set_output_speed(1.0);
  server->step(0.001);
  EXPECT_NEAR(client.read().slip_power_w, 60.0, 1e-2);

  client.set_setpoint(40.0, BrakeMode::torque, 0.0);
  server->step(5.0);
  const auto t = client.read();
  EXPECT_NEAR(t.torque_nm, 40.0, 1e-3);
  // Coming down from 60 N·m the controller uses the falling branch: 0.8 A − 0.04 A play.
  EXPECT_NEAR(t.coil_current_a, 0.76, 1e-6);

  client.disable();
  server->step(0.001);
  EXPECT_FALSE(client.read().status.output_on);
  EXPECT_EQ(client.read().coil_current_a, 0.0);
}

TEST_F(BrakeClientTcp, RampIsFollowed) {
  client.set_setpoint(1.0, BrakeMode::current, 0.5);  // 0.5 A/s
  client.enable();
  server->step(1.0);
  EXPECT_NEAR(client.read().coil_current_a, 0.5, 1e-5);
  EXPECT_FALSE(client.read().status.at_setpoint);
  server->step(1.0);
  server->step(5.0);
  EXPECT_NEAR(client.read().coil_current_a, 1.0, 1e-5);
  EXPECT_TRUE(client.read().status.at_setpoint);
}

TEST_F(BrakeClientTcp, MakeSafeSwitchesOffAndZeroesTheSetpoint) {
  client.set_setpoint(1.0, BrakeMode::current, 0.0);
  client.enable();
  server->step(1.0);
  ASSERT_TRUE(client.read().status.output_on);
  client.make_safe();
  server->step(0.001);
  const auto r = client.read();
  EXPECT_FALSE(r.status.output_on);
  EXPECT_EQ(r.coil_current_a, 0.0);
  client.enable();  // enabling again does not bring the old setpoint back
  server->step(1.0);
  EXPECT_EQ(client.read().coil_current_a, 0.0);
}

TEST_F(BrakeClientTcp, LimitsAreCheckedBeforeWriting) {
  EXPECT_THROW(client.set_setpoint(2.5, BrakeMode::current, 0.0), std::invalid_argument);
  EXPECT_THROW(client.set_setpoint(-1.0, BrakeMode::current, 0.0), std::invalid_argument);
  EXPECT_THROW(client.set_setpoint(150.0, BrakeMode::torque, 0.0), std::invalid_argument);
  EXPECT_EQ(client.transactions(), 0u);
}

TEST_F(BrakeClientTcp, AlarmIsDecodedAndReset) {
  client.set_setpoint(1.0, BrakeMode::current, 0.0);
  client.enable();
  server->step(1.0);
  server->with_controller([](auto& c) { c.physics().set_temperature(85.0); });
  server->step(0.01);
  auto r = client.read();
  EXPECT_TRUE(r.status.alarm);
  EXPECT_TRUE(r.status.over_temperature);
  EXPECT_FALSE(r.status.output_on);
  EXPECT_EQ(r.alarm_code, 1);
  EXPECT_NE(r.alarm_text.find("coil over-temperature"), std::string::npos) << r.alarm_text;
  client.reset_alarm();  // still hot: stays
  EXPECT_TRUE(client.read().status.alarm);
  server->with_controller([](auto& c) { c.physics().set_temperature(40.0); });
  client.reset_alarm();
  r = client.read();
  EXPECT_FALSE(r.status.alarm);
  EXPECT_EQ(r.alarm_code, 0);
  EXPECT_FALSE(r.status.output_on);  // an alarm drops enable: the master must enable again
  client.enable();
  server->step(0.01);
  EXPECT_TRUE(client.read().status.output_on);
}

struct RecordingSink : modbus::BrakeEventSink {
  void on_brake_event(const modbus::BrakeEvent& e) noexcept override {
    std::lock_guard lock(mutex);
    events.push_back(e);
  }
  int count(modbus::BrakeEvent::Kind kind) {
    std::lock_guard lock(mutex);
    int n = 0;
    for (const auto& e : events) n += e.kind == kind;
    return n;
  }
  std::string reason(modbus::BrakeEvent::Kind kind) {
    std::lock_guard lock(mutex);
    for (const auto& e : events)
      if (e.kind == kind) return e.reason;
    return "";
  }
  std::mutex mutex;
  std::vector<modbus::BrakeEvent> events;
};

TEST(BrakeSupervisorTcp, WatchdogTripsWhenHeartbeatsStop) {
  auto server = start_tcp_brake(/*real_time=*/true);
  RecordingSink sink;
  modbus::BrakeSupervisor supervisor(client_config_tcp(server->port()), sink);
  BrakeClient client(client_config_tcp(server->port()));
  client.set_setpoint(1.0, BrakeMode::current, 0.0);
  client.enable();
  supervisor.start();
  ASSERT_TRUE(eventually([&] { return supervisor.heartbeats_sent() >= 10; }));
  auto r = client.read();
  EXPECT_TRUE(r.status.output_on) << r.alarm_text;
  EXPECT_FALSE(r.status.watchdog_tripped);
  EXPECT_EQ(server->with_controller([](auto& c) { return c.holding()[1]; }), 1500);

  supervisor.suspend_heartbeat(true);
  ASSERT_TRUE(eventually([&] { return client.read().status.watchdog_tripped; }));
  r = client.read();
  EXPECT_FALSE(r.status.output_on);
  EXPECT_EQ(r.alarm_code, 2);
  EXPECT_NE(r.alarm_text.find("watchdog"), std::string::npos);
  ASSERT_TRUE(eventually([&] { return sink.count(modbus::BrakeEvent::Kind::alarm_raised) == 1; }));
  EXPECT_NE(sink.reason(modbus::BrakeEvent::Kind::alarm_raised).find("watchdog"),
            std::string::npos);

  supervisor.suspend_heartbeat(false);
  client.reset_alarm();
  ASSERT_TRUE(eventually([&] { return sink.count(modbus::BrakeEvent::Kind::alarm_cleared) == 1; }));
  EXPECT_FALSE(client.read().status.watchdog_tripped);
  EXPECT_EQ(sink.count(modbus::BrakeEvent::Kind::link_lost), 0);
}

TEST(BrakeSupervisorTcp, LinkLossRaisesSafetyEventAndRecovers) {
  auto server = start_tcp_brake(true);
  const int port = server->port();
  RecordingSink sink;
  modbus::BrakeSupervisor supervisor(client_config_tcp(port), sink);
  supervisor.start();
  ASSERT_TRUE(eventually([&] { return supervisor.latest().has_value(); }));
  server.reset();  // the controller goes away
  ASSERT_TRUE(eventually([&] { return sink.count(modbus::BrakeEvent::Kind::link_lost) == 1; }));
  EXPECT_TRUE(supervisor.link_lost());
  EXPECT_NE(sink.reason(modbus::BrakeEvent::Kind::link_lost).find("no valid reply"),
            std::string::npos);
  // It comes back on the same port: the supervisor reconnects and says so.
  simdevices::BrakeServerOptions o;
  o.endpoint = modbus::parse_modbus_endpoint("tcp:127.0.0.1:" + std::to_string(port));
  server = simdevices::start_brake_server(o);
  ASSERT_TRUE(eventually([&] { return sink.count(modbus::BrakeEvent::Kind::link_restored) == 1; }));
  EXPECT_FALSE(supervisor.link_lost());
  // The restarted controller's watchdog was armed again.
  ASSERT_TRUE(eventually(
      [&] { return server->with_controller([](auto& c) { return c.holding()[1]; }) == 1500; }));
  EXPECT_EQ(sink.count(modbus::BrakeEvent::Kind::link_lost), 1);
}

TEST(BrakeSupervisorTcp, NeverConnectedLinkIsReportedLost) {
  // Bind, learn a free port, close: nothing listens there.
  int port = 0;
  {
    auto s = start_tcp_brake();
    port = s->port();
  }
  RecordingSink sink;
  modbus::BrakeSupervisor supervisor(client_config_tcp(port), sink);
  supervisor.start();
  ASSERT_TRUE(eventually([&] { return sink.count(modbus::BrakeEvent::Kind::link_lost) == 1; }));
  EXPECT_FALSE(supervisor.latest().has_value());
  EXPECT_NE(supervisor.last_error().find("connect"), std::string::npos) << supervisor.last_error();
}

}  // namespace
}  // namespace wavebench::testing
