// `wavebench brake ...` end to end against the simulated controller (skipped when the CLI has
// not been built).
#include <gtest/gtest.h>
#include <unistd.h>

#include "brake_test_support.hpp"
#include "peer_process.hpp"

namespace wavebench::testing {
namespace {

const std::string cli = std::string(WAVEBENCH_BINARY_DIR) + "/src/cli/wavebench";

TEST(BrakeCli, SetEnableStatusAndErrors) {
  if (access(cli.c_str(), X_OK) != 0) GTEST_SKIP() << "wavebench CLI not built";
  auto server = start_tcp_brake();
  const std::string link = " --modbus tcp:127.0.0.1:" + std::to_string(server->port());
  int st = -1;
  std::string out = run_command(cli + " brake set 30 --torque --ramp 100" + link, st);
  ASSERT_EQ(st, 0) << out;
  out = run_command(cli + " brake enable" + link, st);
  ASSERT_EQ(st, 0) << out;
  server->step(5.0);
  out = run_command(cli + " brake status --json" + link, st);
  ASSERT_EQ(st, 0) << out;
  EXPECT_NE(out.find("\"output_on\": true"), std::string::npos) << out;
  EXPECT_NE(out.find("\"at_setpoint\": true"), std::string::npos) << out;
  EXPECT_NE(out.find("\"coil_current_a\": 0.6"), std::string::npos) << out;
  EXPECT_NEAR(server->with_controller([](auto& c) { return c.physics().torque_capacity(); }), 30.0,
              1e-6);

  out = run_command(cli + " brake set 5" + link, st);  // 5 A is past limits.max_current_a
  EXPECT_EQ(st, 2) << out;
  EXPECT_NE(out.find("max_current_a"), std::string::npos) << out;

  out = run_command(cli + " brake disable" + link, st);
  ASSERT_EQ(st, 0) << out;
  server->step(0.01);
  EXPECT_FALSE(server->with_controller([](auto& c) { return c.output_on(); }));

  const int port = server->port();
  server.reset();
  out = run_command(
      cli + " brake status --timeout-ms 500 --modbus tcp:127.0.0.1:" + std::to_string(port), st);
  EXPECT_EQ(st, 1) << out;
  EXPECT_NE(out.find("cannot connect"), std::string::npos) << out;
}

}  // namespace
}  // namespace wavebench::testing
