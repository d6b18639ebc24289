// Drive units and optional objects on the in-process simulated bench (issue #9 acceptance):
// a drive whose velocity unit is rpm and one in factor-group units turn the input at the
// dynamic run's 100 rpm within 0.5 %, measured from the output encoder (not from the drive's
// own velocity report); a drive without 0x60F4 completes a static run with the channel
// reported absent; bad factor groups and a limit that needs an absent channel stop the connect.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <numbers>
#include <string>

#include "bench_test_support.hpp"
#include "wavebench/bench/bench_config.hpp"
#include "wavebench/bench/bench_factory.hpp"
#include "wavebench/bench/canopen_bench.hpp"
#include "wavebench/bench/drive_channels.hpp"
#include "wavebench/procedures/dynamic_te_procedure.hpp"
#include "wavebench/procedures/run_executor.hpp"
#include "wavebench/storage/run_store.hpp"

namespace wavebench::bench {
namespace {

namespace fs = std::filesystem;
constexpr double kRadPerSToRpm = 60 / (2 * std::numbers::pi);

BenchConfig bench_config(const char* file) {
  return load_bench_config(fs::path(WAVEBENCH_SOURCE_DIR) / "configs" / "benches" / file);
}

struct Connected {
  explicit Connected(const BenchConfig& config) : sim(config) { sim.bench->connect(); }
  ~Connected() { sim.bench->disconnect(); }
  simdevices::ObjectDictionary& drive_od() { return sim.access->devices().drive().od(); }
  testing::SimBench sim;
};

// The dynamic procedure at its default 100 rpm of the input for one output revolution; the
// input speed from the output encoder's angle over the record, times the ratio.
struct DynamicSpeed {
  double from_encoder_rpm = 0;
  double from_drive_position_rpm = 0;
  std::int32_t target_velocity = 0;  // 0x60FF as the drive holds it during the run
};

DynamicSpeed run_dynamic(Connected& c) {
  procedures::DynamicTeOptions o;  // input_rpm 100
  o.output_revolutions = 1;
  o.run_in_s = 1;
  DynamicSpeed s;
  procedures::DynamicTeProcedure procedure(o);
  // The drive's target velocity is read while the record runs, before the stop zeroes it.
  struct TargetProbe : SampleObserver {
    simdevices::ObjectDictionary* od = nullptr;
    std::int32_t seen = 0;
    void on_sample(const storage::SyncSample&) noexcept override {
      seen = std::max(seen, od->get<std::int32_t>(0x60FF, 0));
    }
  } probe;
  probe.od = &c.drive_od();
  c.sim.bench->add_observer(probe);
  const auto out = procedure.run(*c.sim.bench);
  c.sim.bench->remove_observer(probe);
  s.target_velocity = probe.seen;
  const auto& r = out.result;
  EXPECT_GT(r.time_s.size(), 1000u);
  const double t = r.time_s.back() - r.time_s.front();
  const double turned = r.output_angle_rad.back() - r.output_angle_rad.front();
  const double ratio = c.sim.bench->description().sense.ratio;
  s.from_encoder_rpm = turned / t * ratio * kRadPerSToRpm;
  s.from_drive_position_rpm = r.input_speed_hz * 60;
  return s;
}

TEST(DriveUnitsOnSimulatedBench, RpmDriveRunsTheDynamicRunAt100RpmWithinHalfAPercent) {
  Connected c(bench_config("sim-rpm-drive.yaml"));
  auto& canopen = c.sim.access->canopen();
  EXPECT_NEAR(canopen.drive_channels().units.velocity_per_rad_s(), kRadPerSToRpm, 1e-12);
  EXPECT_TRUE(c.sim.bench->absent_channels().empty());
  const auto s = run_dynamic(c);
  std::printf(
      "rpm drive: 0x60FF = %d, input %.4f rpm from the output encoder, %.4f rpm from "
      "the drive's position\n",
      s.target_velocity, s.from_encoder_rpm, s.from_drive_position_rpm);
  EXPECT_EQ(s.target_velocity, 100);  // written in rpm, not counts/s (218453)
  EXPECT_NEAR(s.from_encoder_rpm, 100, 0.5);
  EXPECT_NEAR(s.from_drive_position_rpm, 100, 0.5);
}

TEST(DriveUnitsOnSimulatedBench, FactorGroupDriveRunsTheDynamicRunAt100RpmWithinHalfAPercent) {
  Connected c(bench_config("sim-factor-group-drive.yaml"));
  const auto& units = c.sim.access->canopen().drive_channels().units;
  // Read from the drive: gear 3/1, feed 360000 per shaft rev -> 120000 per motor rev.
  EXPECT_NEAR(units.position_per_rad() * 2 * std::numbers::pi, 120000, 1e-6);
  EXPECT_NEAR(units.velocity_per_rad_s() * 2 * std::numbers::pi, 120000, 1e-6);
  const auto s = run_dynamic(c);
  std::printf(
      "factor-group drive: 0x60FF = %d, input %.4f rpm from the output encoder, %.4f rpm "
      "from the drive's position\n",
      s.target_velocity, s.from_encoder_rpm, s.from_drive_position_rpm);
  EXPECT_EQ(s.target_velocity, 200000);  // 100/60 rev/s × 120000
  EXPECT_NEAR(s.from_encoder_rpm, 100, 0.5);
  EXPECT_NEAR(s.from_drive_position_rpm, 100, 0.5);
}

TEST(DriveUnitsOnSimulatedBench, DriveWithoutFollowingErrorCompletesAStaticRunChannelAbsent) {
  const auto root =
      fs::temp_directory_path() / ("wavebench-units-" + std::to_string(::getpid()) + "-static");
  fs::remove_all(root);
  {
    Connected c(bench_config("sim-drive-without-following-error.yaml"));
    ASSERT_EQ(c.sim.bench->absent_channels(), std::vector<std::string>{kFollowingErrorChannel});
    storage::RunStore store(root, "test");
    procedures::RunRequest r;
    r.procedure = "static";
    r.options = {{"positions", 4}, {"loads_nm", {0}}, {"window_s", 0.1}};
    r.config_text = "name: sim-drive-without-following-error\n";
    r.twin = false;
    r.report = false;
    const auto out = procedures::execute_run(*c.sim.bench, store, r);
    EXPECT_EQ(out.status, storage::RunStatus::kComplete) << out.reason;
    EXPECT_EQ(out.results.at("absent_channels"), nlohmann::json::array({kFollowingErrorChannel}));
    const auto written = nlohmann::json::parse(std::ifstream(out.dir / "results.json"));
    EXPECT_EQ(written.at("absent_channels"), nlohmann::json::array({kFollowingErrorChannel}));
    EXPECT_FALSE(c.sim.access->canopen().latest_drive().following_error_valid);
    EXPECT_EQ(c.sim.observer.samples.back().flags & storage::kAllChannelsValid,
              storage::kAllChannelsValid);
  }
  fs::remove_all(root);
}

TEST(DriveUnitsOnSimulatedBench, DefaultDriveReportsNoAbsentChannelInItsResults) {
  Connected c(testing::sim_config());
  EXPECT_TRUE(c.sim.bench->absent_channels().empty());
  EXPECT_TRUE(c.sim.access->canopen().latest_drive().following_error_valid);
  // The default units: counts, and 0x6077 per mille of 0x6076 = 1300 mN*m.
  const auto& units = c.sim.access->canopen().drive_channels().units;
  EXPECT_NEAR(units.velocity_per_rad_s() * 2 * std::numbers::pi, 131072, 1e-9);
  EXPECT_NEAR(units.torque_nm_per_unit(), 1.3e-3, 1e-12);
}

TEST(DriveUnitsOnSimulatedBench, FollowingErrorRefusedInTheMappingBecomesAbsent) {
  testing::SimBench sim(testing::sim_config(
      [](BenchConfig& c) { c.description.limits.max_following_error_rad = 0; }));
  // Readable by SDO but not PDO-mappable: the drive refuses it in TPDO2 (06040041).
  sim.access->devices().drive().od().find(0x60F4, 0)->pdo_mappable = false;
  sim.bench->connect();
  const auto& ch = sim.access->canopen().drive_channels();
  ASSERT_EQ(ch.absent.size(), 1u);
  EXPECT_EQ(ch.absent[0].name, kFollowingErrorChannel);
  EXPECT_NE(ch.absent[0].reason.find("06040041"), std::string::npos) << ch.absent[0].reason;
  EXPECT_NE(ch.absent[0].reason.find("TPDO2"), std::string::npos) << ch.absent[0].reason;
  sim.bench->wait_for(0.05);
  EXPECT_TRUE(sim.observer.samples.back().valid(storage::kInputSpeedValid));
  sim.bench->disconnect();
}

std::string connect_error(const BenchConfig& config) {
  testing::SimBench sim(config);
  try {
    sim.bench->connect();
  } catch (const std::exception& e) {
    EXPECT_EQ(sim.bench->state(), BenchLifecycle::kUnconfigured);
    return e.what();
  }
  sim.bench->disconnect();
  return "(connected)";
}

TEST(DriveUnitsOnSimulatedBench, LimitThatNeedsAnAbsentChannelStopsTheConnect) {
  auto config = bench_config("sim-drive-without-following-error.yaml");
  config.description.limits.max_following_error_rad = 4 * std::numbers::pi;
  const auto m = connect_error(config);
  EXPECT_NE(m.find("safety.max_following_error"), std::string::npos) << m;
  EXPECT_NE(m.find("drive.following_error"), std::string::npos) << m;
  EXPECT_NE(m.find("06020000"), std::string::npos) << m;
}

TEST(DriveUnitsOnSimulatedBench, ZeroOrNegativeFactorReadFromTheDriveStopsTheConnect) {
  const auto with_feed = [](std::uint32_t feed, std::uint32_t gear_motor) {
    auto c = bench_config("sim-factor-group-drive.yaml");
    auto devices = std::make_shared<simdevices::SimulatedBenchConfig>(
        c.simulated->devices ? *c.simulated->devices : simdevices::SimulatedBenchConfig{});
    devices->drive.factor_group.feed = feed;
    devices->drive.factor_group.gear_motor_revolutions = gear_motor;
    c.simulated->devices = devices;
    return c;
  };
  auto m = connect_error(with_feed(0, 3));
  EXPECT_NE(m.find("servo drive (node 1)"), std::string::npos) << m;
  EXPECT_NE(m.find("0x6092:01 (feed constant, numerator) = 0: expected an UNSIGNED32 > 0"),
            std::string::npos)
      << m;
  m = connect_error(with_feed(360000, 0xFFFFFFFDU));  // -3 as INTEGER32
  EXPECT_NE(m.find("0x6091:01 (gear ratio, numerator) = 4294967293 (-3 as INTEGER32)"),
            std::string::npos)
      << m;
}

}  // namespace
}  // namespace wavebench::bench
