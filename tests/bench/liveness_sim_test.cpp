// Devices taken as they come (issue 20), on the in-process simulated bench on the simulated
// clock: a drive without a heartbeat producer (no 0x1017) is node-guarded, its check row is
// green, the bench stays inactive without a trip, and silencing it trips the bench naming node
// guarding; a silent bus, and a heartbeat that stops while PDOs go on, trip within the
// heartbeat timeout of wall time (these tests measure wall time, generously bounded).
#include <gtest/gtest.h>

#include <chrono>
#include <memory>
#include <regex>

#include "bench_test_support.hpp"
#include "wavebench/bench/bench_check.hpp"
#include "wavebench/bench/canopen_bench.hpp"
#include "wavebench/simdevices/simulated_bench_config.hpp"

namespace wavebench::bench {
namespace {

using testing::sim_config;
using testing::SimBench;
using Clock = std::chrono::steady_clock;

BenchConfig drive_without_heartbeat_producer() {
  return sim_config([](BenchConfig& c) {
    auto devices = std::make_shared<simdevices::SimulatedBenchConfig>();
    devices->drive.identity.heartbeat_producer = false;
    c.simulated->devices = devices;
  });
}

// "... for N ms ..." of a trip reason.
long silence_ms(const std::string& reason) {
  std::smatch m;
  if (!std::regex_search(reason, m, std::regex(R"(for (\d+) ms)"))) return -1;
  return std::stol(m[1]);
}

// Waits for the trip; returns its reason and the wall time from `since` to the throw.
std::pair<std::string, double> wait_for_trip(SimBench& sim, Clock::time_point since) {
  try {
    sim.bench->wait_for(600.0);
  } catch (const BenchAborted& e) {
    return {e.what(), std::chrono::duration<double>(Clock::now() - since).count()};
  }
  ADD_FAILURE() << "the bench did not trip";
  return {};
}

TEST(NodeGuardingBench, DriveWithoutHeartbeatProducerIsGuardedAndItsCheckRowIsGreen) {
  SimBench sim(drive_without_heartbeat_producer());
  auto& canopen = sim.access->canopen();
  sim.bench->connect();
  EXPECT_EQ(sim.bench->state(), BenchLifecycle::kInactive);
  ASSERT_NE(canopen.node_guards().guard(1), nullptr);
  EXPECT_EQ(canopen.node_guards().guard(3), nullptr);  // the encoder beats
  // The drive got guard time and life time factor.
  EXPECT_EQ(sim.access->devices().drive().od().get<std::uint16_t>(0x100C, 0), 100U);
  EXPECT_EQ(sim.access->devices().drive().od().get<std::uint8_t>(0x100D, 0), 3U);
  // A few seconds of bench time, and at least a second of wall time, inactive and untripped.
  const auto t0 = Clock::now();
  while (Clock::now() - t0 < std::chrono::seconds(1)) sim.bench->wait_for(0.5);
  EXPECT_EQ(sim.bench->state(), BenchLifecycle::kInactive) << sim.bench->fault_reason();
  const auto* guard = canopen.node_guards().guard(1);
  EXPECT_GE(guard->answers(), 5U);
  EXPECT_EQ(guard->toggle_errors(), 0U);
  const auto stats = sim.bench->acquisition_stats();
  bool listed = false;
  for (const auto& n : stats.nodes) {
    if (n.node != 1) continue;
    listed = true;
    EXPECT_EQ(n.supervision, "node guarding");
    EXPECT_EQ(n.nmt_state, "operational");
    EXPECT_GT(n.heartbeats, 0U);
  }
  EXPECT_TRUE(listed);

  const auto report = check_bench(canopen, {});
  const auto table = format_check_table(report);
  bool row = false;
  for (const auto& r : report.rows) {
    if (r.device.find("node 1") == std::string::npos) continue;
    EXPECT_NE(r.item, "heartbeat") << table;
    if (r.item != "node guarding") continue;
    row = true;
    EXPECT_TRUE(r.ok) << table;
    EXPECT_NE(r.detail.find("guard time 100 ms"), std::string::npos) << r.detail;
  }
  EXPECT_TRUE(row) << table;
  EXPECT_TRUE(report.all_green()) << table;
}

TEST(NodeGuardingBench, SilencedGuardedDriveTripsWithinTheLifeTimeNamingNodeGuarding) {
  SimBench sim(drive_without_heartbeat_producer());
  sim.bench->connect();
  sim.bench->wait_for(0.5);
  const auto silenced = Clock::now();
  sim.access->devices().drive().set_silent(true);
  const auto [reason, wall] = wait_for_trip(sim, silenced);
  EXPECT_NE(reason.find("node guarding of node 1 (servo drive)"), std::string::npos) << reason;
  EXPECT_NE(reason.find("guard time 100 ms"), std::string::npos) << reason;
  // Since its last answer: at most a guard time before the silence, then the life time.
  const auto ms = silence_ms(reason);
  EXPECT_GE(ms, 300) << reason;
  EXPECT_LE(ms, 100 + 300 + 250) << reason;
  // The throw also waits out the quick stop's bound (quick_stop_timeout + 0.5 s).
  EXPECT_LT(wall, 0.3 + 0.25 + 0.6) << reason;
  EXPECT_EQ(sim.bench->state(), BenchLifecycle::kFault);
}

TEST(WallClockHeartbeat, SilentBusOnTheSimulatedClockTripsWithinTheHeartbeatTimeout) {
  SimBench sim(sim_config());
  ASSERT_TRUE(sim.access->canopen().config().description.simulated_clock);
  sim.bench->connect();
  sim.bench->wait_for(0.5);
  const auto silenced = Clock::now();
  sim.access->devices().set_silent(true);
  const auto [reason, wall] = wait_for_trip(sim, silenced);
  EXPECT_NE(reason.find("heartbeat of node"), std::string::npos) << reason;
  // The wall-clock silence, truthfully: at most a producer time before the cut, then 500 ms.
  const auto ms = silence_ms(reason);
  EXPECT_GE(ms, 500) << reason;
  EXPECT_LE(ms, 500 + 250) << reason;
  EXPECT_LT(wall, 0.5 + 0.25 + 0.6) << reason;
}

TEST(WallClockHeartbeat, HeartbeatStoppingWhilePdosGoOnTripsWithinTheTimeoutOfWallTime) {
  SimBench sim(sim_config());
  sim.bench->connect();
  sim.bench->wait_for(0.5);
  const auto stopped = Clock::now();
  const double bench_before = sim.bench->now();
  sim.access->devices().encoder().od().set<std::uint16_t>(0x1017, 0, 0);
  const auto [reason, wall] = wait_for_trip(sim, stopped);
  EXPECT_NE(reason.find("heartbeat of node 3"), std::string::npos) << reason;
  const auto ms = silence_ms(reason);
  EXPECT_GE(ms, 500) << reason;
  EXPECT_LE(ms, 500 + 250) << reason;
  EXPECT_LT(wall, 0.5 + 0.25 + 0.6) << reason;
  // Bench time ran faster than real time meanwhile (it is not what judged the loss).
  std::printf("bench time %.2f s over %.2f s of wall time\n", sim.bench->now() - bench_before,
              wall);
}

}  // namespace
}  // namespace wavebench::bench
