#include <gtest/gtest.h>

#include "brake_test_support.hpp"

namespace wavebench::testing {
namespace {

using modbus::BrakeClient;
using modbus::ModbusError;
using modbus::ModbusErrorKind;
using simdevices::BrakeFault;
using simdevices::BrakeFaultKind;

class BrakeFaultsTcp : public ::testing::Test {
 protected:
  void inject(BrakeFaultKind kind, int requests = -1) {
    BrakeFault f;
    f.kind = kind;
    f.delay = 2500ms;  // well past the 1000 ms response timeout
    f.requests = requests;
    server->inject_fault(f);
  }
  // The error a read gets, and that it came within a bound (hang check, not a speed check).
  ModbusError read_error() {
    const auto t0 = std::chrono::steady_clock::now();
    try {
      client.read();
    } catch (const ModbusError& e) {
      EXPECT_LT(std::chrono::steady_clock::now() - t0, 10s) << "hung past the timeouts";
      return e;
    }
    ADD_FAILURE() << "read succeeded under a fault";
    return ModbusError(ModbusErrorKind::invalid_argument, "none");
  }
  bool recovers() {
    return eventually([&] {
      try {
        return client.read().temperature_c == 25.0;
      } catch (const ModbusError&) {
        return false;
      }
    });
  }
  std::unique_ptr<simdevices::BrakeServer> server = start_tcp_brake();
  BrakeClient client{client_config_tcp(server->port())};
};

TEST_F(BrakeFaultsTcp, DelayedReplyTimesOutThenRecovers) {
  client.connect();
  inject(BrakeFaultKind::delayed_reply);
  const auto e = read_error();
  EXPECT_EQ(e.kind(), ModbusErrorKind::timeout) << e.what();
  EXPECT_NE(std::string(e.what()).find("response timeout 1000 ms"), std::string::npos) << e.what();
  server->clear_fault();
  EXPECT_TRUE(recovers());
}

TEST_F(BrakeFaultsTcp, ShortDelayWithinTimeoutIsFine) {
  BrakeFault f;
  f.kind = BrakeFaultKind::delayed_reply;
  f.delay = 50ms;
  server->inject_fault(f);
  EXPECT_EQ(client.read().temperature_c, 25.0);
  EXPECT_GE(server->faults_committed(), 1u);
}

TEST_F(BrakeFaultsTcp, ExceptionResponseIsNamed) {
  client.connect();
  inject(BrakeFaultKind::exception_response);
  const auto e = read_error();
  EXPECT_EQ(e.kind(), ModbusErrorKind::exception);
  EXPECT_EQ(e.exception_code(), 6);
  EXPECT_NE(std::string(e.what()).find("server device busy"), std::string::npos) << e.what();
  EXPECT_TRUE(client.connected());  // a refusal is no reason to drop the link
  server->clear_fault();
  EXPECT_TRUE(recovers());
}

TEST_F(BrakeFaultsTcp, DroppedConnectionReconnects) {
  client.connect();
  inject(BrakeFaultKind::dropped_connection, 1);
  const auto e = read_error();
  EXPECT_EQ(e.kind(), ModbusErrorKind::connection) << e.what();
  EXPECT_FALSE(client.connected());
  EXPECT_TRUE(recovers());
  EXPECT_TRUE(client.connected());
}

TEST_F(BrakeFaultsTcp, WrongUnitIdIsRejected) {
  client.connect();
  inject(BrakeFaultKind::wrong_unit_id);
  const auto e = read_error();
  EXPECT_EQ(e.kind(), ModbusErrorKind::wrong_unit) << e.what();
  EXPECT_NE(std::string(e.what()).find("unit id 2"), std::string::npos) << e.what();
  server->clear_fault();
  EXPECT_TRUE(recovers());
}

TEST_F(BrakeFaultsTcp, GarbageBytesAreRejected) {
  client.connect();
  inject(BrakeFaultKind::garbage_bytes);
  const auto e = read_error();
  EXPECT_EQ(e.kind(), ModbusErrorKind::bad_reply) << e.what();
  server->clear_fault();
  EXPECT_TRUE(recovers());
}

TEST_F(BrakeFaultsTcp, NoReconnectAttemptsDuringTheBackoff) {
  const int port = server->port();
  server.reset();
  auto cfg = client_config_tcp(port);
  cfg.link.reconnect_initial_backoff = 30s;  // longer than the test: no second attempt
  cfg.link.reconnect_max_backoff = 120s;
  BrakeClient lonely(cfg);
  int refused = 0;
  for (int i = 0; i < 5; ++i) {
    try {
      lonely.read();
    } catch (const ModbusError& e) {
      EXPECT_EQ(e.kind(), ModbusErrorKind::not_connected) << e.what();
      if (i > 0) {
        EXPECT_NE(std::string(e.what()).find("next attempt in"), std::string::npos);
      }
      ++refused;
    }
  }
  EXPECT_EQ(refused, 5);
  EXPECT_EQ(lonely.backoff().failures(), 1);
  EXPECT_EQ(lonely.backoff().current_delay(), 60s);
}

TEST(ReconnectBackoff, DoublesUpToTheCeilingAndResets) {
  modbus::ReconnectBackoff b(100ms, 700ms);
  const auto t0 = modbus::ReconnectBackoff::Clock::time_point{} + 1h;
  EXPECT_TRUE(b.due(t0));
  b.failed(t0);
  EXPECT_FALSE(b.due(t0 + 99ms));
  EXPECT_TRUE(b.due(t0 + 100ms));
  b.failed(t0 + 100ms);  // waits 200 ms
  EXPECT_FALSE(b.due(t0 + 299ms));
  EXPECT_TRUE(b.due(t0 + 300ms));
  b.failed(t0 + 300ms);  // 400 ms
  b.failed(t0 + 700ms);  // 700 ms (ceiling), not 800
  EXPECT_FALSE(b.due(t0 + 1399ms));
  EXPECT_TRUE(b.due(t0 + 1400ms));
  EXPECT_EQ(b.current_delay(), 700ms);
  EXPECT_EQ(b.failures(), 4);
  b.succeeded();
  EXPECT_EQ(b.current_delay(), 100ms);
  EXPECT_TRUE(b.due(t0));
}

}  // namespace
}  // namespace wavebench::testing
