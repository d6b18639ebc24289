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
    f.delay = 800ms;  // well past the 300 ms response timeout
    f.requests = requests;
    server->inject_fault(f);
  }
  // The error a read gets, and that it came within a bound (hang check, not a speed check).
  ModbusError read_error() {
    const auto t0 = std::chrono::steady_clock::now();
    try {
      client.read();
    } catch (const ModbusError& e) {
      EXPECT_LT(std::chrono::steady_clock::now() - t0, 5s) << "hung past the timeouts";
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
  EXPECT_NE(std::string(e.what()).find("response timeout 300 ms"), std::string::npos) << e.what();
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

TEST_F(BrakeFaultsTcp, BackoffGrowsWhileTheControllerIsAway) {
  const int port = server->port();
  server.reset();
  BrakeClient lonely(client_config_tcp(port));
  int refused = 0;
  for (int i = 0; i < 6; ++i) {
    try {
      lonely.read();
    } catch (const ModbusError& e) {
      EXPECT_EQ(e.kind(), ModbusErrorKind::not_connected) << e.what();
      ++refused;
    }
    std::this_thread::sleep_for(30ms);
  }
  EXPECT_EQ(refused, 6);
  // Calls during the backoff do not count as attempts: fewer attempts than calls.
  EXPECT_GE(lonely.backoff().failures(), 1);
  EXPECT_LT(lonely.backoff().failures(), 6);
  EXPECT_GT(lonely.backoff().current_delay(), 20ms);
  EXPECT_LE(lonely.backoff().current_delay(), 200ms);
}

}  // namespace
}  // namespace wavebench::testing
