// Devices whose TPDO mapping cannot be written (issue 20) on the in-process simulated bench:
// the simulated drive, encoder and torque sensor with read-only TPDO parameters laid out
// otherwise than the bench maps them (simbench `fixed_tpdo_mapping`). The bench reads them back
// and uses them as found: the commissioning check is green saying so, and static and dynamic
// runs give the default bench's figures; a fixed mapping without the statusword is refused
// naming 0x6041.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <memory>
#include <string>

#include "bench_test_support.hpp"
#include "wavebench/bench/bench_check.hpp"
#include "wavebench/bench/canopen_bench.hpp"
#include "wavebench/canopen/sdo_abort.hpp"
#include "wavebench/procedures/dynamic_te_procedure.hpp"
#include "wavebench/procedures/static_te_procedure.hpp"
#include "wavebench/simdevices/simulated_bench_config.hpp"

namespace wavebench::bench {
namespace {

// The drive as the issue's example: TPDO1 [position, statusword], TPDO2 [velocity] (no 0x60F4,
// so the following-error limit goes); encoder and torque sensor fixed as the bench would map.
constexpr const char* kIssueLayout = R"(
simbench:
  drive:
    fixed_tpdo_mapping: {tpdo1: ["0x6064:0/32", "0x6041:0/16"], tpdo2: ["0x606C:0/32"]}
  encoder:
    fixed_tpdo_mapping: {tpdo1: ["0x6004:0/32"]}
  torque_sensor:
    fixed_tpdo_mapping: {tpdo1: ["0x6130:1/32"]}
)";

// Velocity in TPDO1, position in TPDO2: each value in the other PDO than the bench's default.
constexpr const char* kSwappedLayout = R"(
simbench:
  drive:
    fixed_tpdo_mapping: {tpdo1: ["0x606C:0/32", "0x6041:0/16"],
                         tpdo2: ["0x6064:0/32", "0x60F4:0/32"]}
)";

constexpr const char* kNoStatusword = R"(
simbench:
  drive:
    fixed_tpdo_mapping: {tpdo1: ["0x6064:0/32"], tpdo2: ["0x606C:0/32"]}
)";

BenchConfig with_simbench(const char* yaml, bool following_error_limit = true) {
  return testing::sim_config([&](BenchConfig& c) {
    const auto base =
        c.simulated->devices ? *c.simulated->devices : simdevices::SimulatedBenchConfig{};
    c.simulated->devices = std::make_shared<const simdevices::SimulatedBenchConfig>(
        simdevices::parse_simulated_bench_config(yaml, base));
    if (!following_error_limit) c.description.limits.max_following_error_rad = 0;
  });
}

const CheckRow* row(const CheckReport& r, const std::string& device, const std::string& item) {
  for (const auto& x : r.rows)
    if (x.device.find(device) != std::string::npos && x.item == item) return &x;
  return nullptr;
}

TEST(FixedPdoMapping, CheckIsGreenSayingUsedAsFound) {
  testing::SimBench sim(with_simbench(kIssueLayout, false));
  auto* canopen = canopen_bench_of(*sim.bench);
  ASSERT_NE(canopen, nullptr);
  const auto report = check_bench(*canopen);
  const auto table = format_check_table(report);
  std::printf("%s", table.c_str());
  EXPECT_TRUE(report.all_green()) << table;
  const auto* drive = row(report, "servo drive", "PDO mapping");
  ASSERT_NE(drive, nullptr) << table;
  EXPECT_EQ(drive->detail,
            "fixed mapping, used as found: TPDO1 [0x6064:0/32, 0x6041:0/16], TPDO2 "
            "[0x606C:0/32] (read back)");
  const auto* encoder = row(report, "output encoder", "PDO mapping");
  ASSERT_NE(encoder, nullptr) << table;
  EXPECT_EQ(encoder->detail, "fixed mapping, used as found: TPDO1 [0x6004:0/32] (read back)");
  const auto* torque = row(report, "torque sensor", "PDO mapping");
  ASSERT_NE(torque, nullptr) << table;
  EXPECT_EQ(torque->detail, "fixed mapping, used as found: TPDO1 [0x6130:1/32] (read back)");
  // 0x60F4 is in no fixed TPDO: the channel is absent, named with the mapping.
  ASSERT_EQ(sim.bench->absent_channels(), std::vector<std::string>{kFollowingErrorChannel});
  EXPECT_NE(canopen->drive_channels().absent[0].reason.find("fixed TPDOs"), std::string::npos);

  // The simulated drive refuses the remap as the real ones do: 06010002.
  std::error_code ec;
  canopen->master().sdo(canopen->config().can.drive_node).write<std::uint8_t>(0x1A00, 0, 0, ec);
  EXPECT_EQ(ec, canopen::make_error_code(canopen::SdoAbort::read_only));
  // Every sample complete: statusword, position and speed from where the drive put them.
  sim.bench->wait_for(0.05);
  ASSERT_FALSE(sim.observer.samples.empty());
  EXPECT_EQ(sim.observer.samples.back().flags & storage::kAllChannelsValid,
            storage::kAllChannelsValid);
  EXPECT_TRUE(canopen->latest_drive().status_valid);
  sim.bench->disconnect();
}

TEST(FixedPdoMapping, ShippedExampleConfigChecksGreen) {
  testing::SimBench sim(load_bench_config(std::filesystem::path(WAVEBENCH_SOURCE_DIR) / "configs" /
                                          "benches" / "sim-fixed-pdo-drive.yaml"));
  const auto report = check_bench(*canopen_bench_of(*sim.bench));
  const auto table = format_check_table(report);
  EXPECT_TRUE(report.all_green()) << table;
  const auto* drive = row(report, "servo drive", "PDO mapping");
  ASSERT_NE(drive, nullptr) << table;
  EXPECT_EQ(
      drive->detail.rfind("fixed mapping, used as found: TPDO1 [0x6064:0/32, 0x6041:0/16]", 0), 0U)
      << drive->detail;
  sim.bench->disconnect();
}

TEST(FixedPdoMapping, WithoutTheStatuswordTheConnectIsRefusedAndTheCheckIsRedNamingIt) {
  const auto config = with_simbench(kNoStatusword, false);
  {
    testing::SimBench sim(config);
    try {
      sim.bench->connect();
      FAIL() << "expected the connect to be refused";
    } catch (const std::exception& e) {
      EXPECT_NE(std::string(e.what()).find("TPDO1 fixed [0x6064:0/32], TPDO2 fixed [0x606C:0/32]: "
                                           "0x6041:0 statusword not mapped in any TPDO"),
                std::string::npos)
          << e.what();
    }
    EXPECT_EQ(sim.bench->state(), BenchLifecycle::kUnconfigured);
  }
  testing::SimBench sim(config);
  const auto report = check_bench(*canopen_bench_of(*sim.bench));
  const auto table = format_check_table(report);
  EXPECT_FALSE(report.all_green());
  const auto* drive = row(report, "servo drive", "PDO mapping");
  ASSERT_NE(drive, nullptr) << table;
  EXPECT_FALSE(drive->ok);
  EXPECT_NE(drive->detail.find("0x6041:0 statusword not mapped in any TPDO"), std::string::npos)
      << table;
}

struct Figures {
  double static_mean_arcmin = 0, static_p2p_arcmin = 0;
  double dynamic_mean_arcsec = 0, dynamic_p2p_arcsec = 0, dynamic_rms_arcsec = 0;
  double input_speed_hz = 0;
};

Figures run_static_and_dynamic(const BenchConfig& config) {
  testing::SimBench sim(config);
  sim.bench->connect();
  procedures::StaticTeOptions s;
  s.positions = 4;
  s.loads_nm = {0};
  s.window_s = 0.1;
  const auto st = procedures::StaticTeProcedure(s).run(*sim.bench);
  procedures::DynamicTeOptions d;
  d.input_rpm = 1000;
  d.output_revolutions = 1;
  d.run_in_s = 0.5;
  const auto dy = procedures::DynamicTeProcedure(d).run(*sim.bench);
  sim.bench->disconnect();
  Figures f;
  EXPECT_FALSE(st.result.passes.empty());
  if (!st.result.passes.empty()) {
    f.static_mean_arcmin = st.result.passes[0].mean_arcmin;
    f.static_p2p_arcmin = st.result.passes[0].p2p_arcmin;
  }
  f.dynamic_mean_arcsec = dy.result.mean_arcsec;
  f.dynamic_p2p_arcsec = dy.result.p2p_arcsec;
  f.dynamic_rms_arcsec = dy.result.rms_arcsec;
  f.input_speed_hz = dy.result.input_speed_hz;
  return f;
}

// The simulated bench is seeded: the same gear and noise seeds on both benches. The tolerances
// are those of the encoder noise (0.5 arcsec 1-sigma per sample), not of the mapping: static
// means average 100 samples per position (0.05 arcsec), so 0.01 arcmin (0.6 arcsec, > 10 sigma)
// is far outside; a dynamic p2p is an extreme of thousands of noisy samples, within +-4 sigma
// of the noise either way (4 arcsec).
TEST(FixedPdoMapping, StaticAndDynamicRunsGiveTheDefaultDrivesFigures) {
  const auto fixed = run_static_and_dynamic(with_simbench(kSwappedLayout));
  const auto plain = run_static_and_dynamic(testing::sim_config());
  std::printf(
      "static mean %.5f / %.5f arcmin, p2p %.5f / %.5f arcmin; dynamic mean %.3f / %.3f, p2p "
      "%.3f / %.3f, rms %.3f / %.3f arcsec, input %.4f / %.4f Hz (fixed / default)\n",
      fixed.static_mean_arcmin, plain.static_mean_arcmin, fixed.static_p2p_arcmin,
      plain.static_p2p_arcmin, fixed.dynamic_mean_arcsec, plain.dynamic_mean_arcsec,
      fixed.dynamic_p2p_arcsec, plain.dynamic_p2p_arcsec, fixed.dynamic_rms_arcsec,
      plain.dynamic_rms_arcsec, fixed.input_speed_hz, plain.input_speed_hz);
  EXPECT_NEAR(fixed.static_mean_arcmin, plain.static_mean_arcmin, 0.01);
  EXPECT_NEAR(fixed.static_p2p_arcmin, plain.static_p2p_arcmin, 0.02);
  EXPECT_NEAR(fixed.dynamic_mean_arcsec, plain.dynamic_mean_arcsec, 0.5);
  EXPECT_NEAR(fixed.dynamic_rms_arcsec, plain.dynamic_rms_arcsec, 0.5);
  EXPECT_NEAR(fixed.dynamic_p2p_arcsec, plain.dynamic_p2p_arcsec, 4.0);
  EXPECT_NEAR(fixed.input_speed_hz, plain.input_speed_hz, 1e-3 * plain.input_speed_hz);
  EXPECT_GT(plain.input_speed_hz, 15);  // 1000 rpm
}

}  // namespace
}  // namespace wavebench::bench
