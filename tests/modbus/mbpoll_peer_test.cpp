// mbpoll (Debian's independent Modbus master) reads and writes the simulated controller.
#include <gtest/gtest.h>

#include "brake_test_support.hpp"
#include "peer_process.hpp"

namespace wavebench::testing {
namespace {

class MbpollPeer : public ::testing::Test {
 protected:
  void SetUp() override {
    if (access("/usr/bin/mbpoll", X_OK) != 0) GTEST_SKIP() << "mbpoll not installed";
  }
  std::string mbpoll(const std::string& args, int& status) {
    return run_command(
        "/usr/bin/mbpoll -m tcp -p " + std::to_string(server->port()) + " -a 1 -0 -1 -o 2 " + args,
        status);
  }
  std::unique_ptr<simdevices::BrakeServer> server = start_tcp_brake();
};

TEST_F(MbpollPeer, WritesSetpointAndEnableThenReadsCurrentAndTorque) {
  int st = 0;
  std::string out = mbpoll("-t 4:float -B -r 10 127.0.0.1 1.5", st);
  ASSERT_EQ(st, 0) << out;
  out = mbpoll("-t 4 -r 0 127.0.0.1 1", st);
  ASSERT_EQ(st, 0) << out;
  server->step(5.0);
  out = mbpoll("-t 3:float -B -r 10 -c 2 127.0.0.1", st);
  ASSERT_EQ(st, 0) << out;
  // mbpoll prints one "[ref]: value" line per value.
  EXPECT_NE(out.find("[10]: \t1.5"), std::string::npos) << out;
  EXPECT_NE(out.find("[12]: \t75"), std::string::npos) << out;
  out = mbpoll("-t 3 -r 0 127.0.0.1", st);
  ASSERT_EQ(st, 0) << out;
  EXPECT_NE(out.find("[0]: \t33"), std::string::npos) << out;  // output on + at setpoint
  // The controller saw the same values through its registers.
  EXPECT_NEAR(server->with_controller([](auto& c) { return c.physics().coil_current(); }), 1.5,
              1e-6);
}

TEST_F(MbpollPeer, ReadsTheWatchdogRegisterItWrote) {
  int st = 0;
  std::string out = mbpoll("-t 4 -r 1 127.0.0.1 250", st);
  ASSERT_EQ(st, 0) << out;
  out = mbpoll("-t 4 -r 1 127.0.0.1", st);
  ASSERT_EQ(st, 0) << out;
  EXPECT_NE(out.find("[1]: \t250"), std::string::npos) << out;
  server->step(0.3);
  out = mbpoll("-t 3 -r 20 127.0.0.1", st);
  EXPECT_NE(out.find("[20]: \t2"), std::string::npos) << out;  // watchdog alarm
}

TEST_F(MbpollPeer, OutOfMapAddressGetsAnException) {
  int st = 0;
  const std::string out = mbpoll("-t 3 -r 40 127.0.0.1", st);
  EXPECT_NE(out.find("Illegal data address"), std::string::npos) << out;
}

TEST(MbpollPeerRtu, ReadsAndWritesOverAPty) {
  if (access("/usr/bin/mbpoll", X_OK) != 0) GTEST_SKIP() << "mbpoll not installed";
  simdevices::PtyPair pty;
  simdevices::BrakeServerOptions o;
  o.endpoint = modbus::parse_modbus_endpoint("rtu:" + pty.slave_path());
  o.rtu_fd = pty.release_master();
  o.real_time = false;
  auto server = simdevices::start_brake_server(o);
  const std::string base =
      "/usr/bin/mbpoll -m rtu -b 19200 -P none -a 1 -0 -1 -o 2 " + pty.slave_path() + " ";
  int st = 0;
  std::string out = run_command(base + "-t 4:float -B -r 10 1.25", st);
  ASSERT_EQ(st, 0) << out;
  out = run_command(base + "-t 4 -r 0 1", st);
  ASSERT_EQ(st, 0) << out;
  server->step(5.0);
  out = run_command(base + "-t 3:float -B -r 10 -c 2", st);
  ASSERT_EQ(st, 0) << out;
  EXPECT_NE(out.find("[10]: \t1.25"), std::string::npos) << out;
  EXPECT_NE(out.find("[12]: \t62.5"), std::string::npos) << out;
}

}  // namespace
}  // namespace wavebench::testing
