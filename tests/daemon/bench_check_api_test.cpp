// GET /api/bench/check over HTTP against wavebenchd's parts on the in-process simulated bench:
// every row green, nothing moved (the drive stays switch-on disabled), the bench stays ready.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "test_dir.hpp"
#include "wavebench/bench/bench_config.hpp"
#include "wavebench/bench/bench_factory.hpp"
#include "wavebench/daemon/daemon.hpp"
#include "wavebench/daemon/daemon_client.hpp"

namespace wavebench::daemon::testing {
namespace {

TEST(BenchCheckApi, AllGreenOnTheSimulatedBenchAndNothingMoves) {
  const auto dir = fresh_test_dir();
  const auto config = bench::default_simulated_bench_config();
  DaemonSetup setup;
  setup.bench_factory = [config] { return bench::make_bench(config); };
  setup.launcher = make_executor_run_launcher();
  setup.bench_check = make_commissioning_check();
  setup.runs_dir = dir / "runs";
  setup.port = 0;
  setup.token = "0123456789abcdef0123456789abcdef";
  setup.config_text = config.text;
  Daemon daemon(std::move(setup));
  daemon.start();
  DaemonClient client("http://127.0.0.1:" + std::to_string(daemon.port()), "");

  const auto reply = client.get("/api/bench/check");
  ASSERT_EQ(reply.status, 200) << reply.body.dump();
  EXPECT_EQ(reply.body["bench"], "sim");
  ASSERT_TRUE(reply.body["rows"].is_array());
  EXPECT_GT(reply.body["rows"].size(), 30u);  // three devices' objects, bus, brake
  for (const auto& row : reply.body["rows"]) {
    EXPECT_TRUE(row["ok"].get<bool>()) << row.dump();
  }
  EXPECT_TRUE(reply.body["all_green"].get<bool>());

  const auto status = client.get("/api/status");
  EXPECT_EQ(status.body["state"], "ready") << status.body.dump();
  // Nothing moved: the input shaft stands still in the samples around the check (below the
  // 0.05 rad/s = 0.5 rpm the bench itself takes for standing still; the disabled simulated
  // drive shows a few mrad/s of residual speed).
  const auto live = client.get("/api/live?limit=20");
  ASSERT_EQ(live.status, 200) << live.body.dump();
  ASSERT_FALSE(live.body["samples"].empty());
  for (const auto& sample : live.body["samples"]) {
    EXPECT_LT(std::abs(sample.value("input_speed_rad_s", 0.0)), 0.05) << sample.dump();
  }
  daemon.shutdown("test done");
}

}  // namespace
}  // namespace wavebench::daemon::testing
