// Bench configs: the shipped files load, values carry units, errors name key, value, expected.
#include "wavebench/bench/bench_config.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "wavebench/bench/bench_factory.hpp"
#include "wavebench/config/config_error.hpp"

namespace wavebench::bench {
namespace {

const std::filesystem::path kConfigs = std::filesystem::path(WAVEBENCH_SOURCE_DIR) / "configs";

TEST(BenchConfig, DefaultSimulatedBenchLoads) {
  const auto c = default_simulated_bench_config();
  EXPECT_TRUE(c.in_process());
  EXPECT_EQ(c.clock, BenchClockKind::kSimulated);
  EXPECT_TRUE(c.description.simulated_clock);
  EXPECT_DOUBLE_EQ(c.description.sync_period_s, 1e-3);
  EXPECT_DOUBLE_EQ(c.description.sense.ratio, 100);
  EXPECT_EQ(c.description.sense.direction_sign, 1);
  EXPECT_DOUBLE_EQ(c.description.twin_gear.geometry.ratio, 100);
  EXPECT_EQ(c.can.drive_node, 1);
  EXPECT_EQ(c.can.encoder_node, 3);
  EXPECT_EQ(c.can.torque_node, 4);
  EXPECT_EQ(c.torque_sensor.sensor.index, 0x6130);
  EXPECT_EQ(c.torque_sensor.sensor.sub, 1);
  EXPECT_NEAR(c.description.output_encoder_noise_rad, 0.5 / 3600 * M_PI / 180, 1e-12);
  EXPECT_NEAR(c.description.limits.max_input_speed_rad_s, 3000 * 2 * M_PI / 60, 1e-9);
  EXPECT_NEAR(c.description.limits.max_te_excursion_rad, 30.0 / 60 * M_PI / 180, 1e-12);
  EXPECT_DOUBLE_EQ(c.description.limits.heartbeat_timeout_s, 0.5);
  EXPECT_EQ(c.brake.link.link_loss_timeout, std::chrono::milliseconds(1000));
  ASSERT_TRUE(c.simulated.has_value());
  EXPECT_TRUE(std::filesystem::exists(c.simulated->true_gear_case));
  EXPECT_EQ(c.simulated->true_gear_case.filename(), "sim-true-gear.yaml");
  EXPECT_FALSE(c.text.empty());
}

TEST(BenchConfig, VcanSimbenchConfigLoads) {
  const auto c = load_bench_config(kConfigs / "benches" / "vcan-simbench.yaml");
  EXPECT_FALSE(c.in_process());
  EXPECT_EQ(c.can.interface, "vcan0");
  EXPECT_EQ(c.brake.link.endpoint.port, 1502);
  EXPECT_EQ(c.brake.link.endpoint.host, "127.0.0.1");
  EXPECT_FALSE(c.encoder.counts_per_turn.has_value());
  EXPECT_FALSE(c.simulated.has_value());
}

TEST(BenchConfig, ArgumentSimMeansTheDefault) {
  EXPECT_EQ(bench_config_from_argument("sim").description.name, "sim");
}

config::ConfigError parse_error(const std::string& yaml) {
  try {
    parse_bench_config(yaml, kConfigs / "benches", "test.yaml");
  } catch (const config::ConfigError& e) {
    return e;
  }
  ADD_FAILURE() << "no error for:\n" << yaml;
  return config::ConfigError("", "", "");
}

TEST(BenchConfig, ErrorsNameKeyValueAndExpectation) {
  auto e = parse_error("sync_period: 1 parsec\n");
  EXPECT_EQ(e.key(), "sync_period");
  EXPECT_EQ(e.source(), "test.yaml");

  e = parse_error("sync_period: \"3 N*m\"\n");
  EXPECT_EQ(e.key(), "sync_period");

  e = parse_error("clock: fast\n");
  EXPECT_EQ(e.key(), "clock");
  EXPECT_EQ(e.value(), "fast");
  EXPECT_NE(e.expected().find("real|simulated"), std::string::npos) << e.what();

  e = parse_error("colck: real\n");
  EXPECT_EQ(e.key(), "colck");

  e = parse_error("can: {nodes: {drive: 200}}\n");
  EXPECT_EQ(e.key(), "can.nodes.drive");
  EXPECT_EQ(e.value(), "200");

  e = parse_error("can: {nodes: {drive: 3}}\n");
  EXPECT_EQ(e.key(), "can.nodes");

  e = parse_error("torque_sensor: {object: \"0x61zz:1\"}\n");
  EXPECT_EQ(e.key(), "torque_sensor.object");

  e = parse_error("safety: {max_input_speed: \"3 A\"}\n");
  EXPECT_EQ(e.key(), "safety.max_input_speed");

  e = parse_error("gear: {ratio: 50}\ntwin_case: ../twin/bench-unit-seed004.yaml\n");
  EXPECT_EQ(e.key(), "gear.ratio");

  e = parse_error("brake: {link: {endpoint: \"udp:1\"}}\n");
  // The brake map is read by the same reader: its refusal names the whole key path.
  EXPECT_EQ(e.key(), "brake.link.endpoint");
  EXPECT_EQ(e.value(), "udp:1");
  EXPECT_EQ(e.source(), "test.yaml");

  e = parse_error("simulated: {simbench: {drive: {node_id: 300}}}\n");
  EXPECT_EQ(e.key(), "simulated.simbench.drive.node_id");
  EXPECT_EQ(e.value(), "300");
  EXPECT_EQ(e.source(), "test.yaml");

  // A key written without a value is refused, never taken as "limit off".
  e = parse_error("safety: {max_input_speed: }\n");
  EXPECT_EQ(e.key(), "safety.max_input_speed");
  EXPECT_NE(e.expected().find("leave the key out"), std::string::npos) << e.what();
}

// The quick stop's confirmation time: 50 ms by default, any time unit, refused when 0, negative,
// above 10 s or not a time.
TEST(BenchConfig, QuickStopTimeoutTakesATime) {
  EXPECT_DOUBLE_EQ(default_simulated_bench_config().can.quick_stop_timeout_s, 0.05);
  EXPECT_DOUBLE_EQ(
      parse_bench_config("can: {quick_stop_timeout: \"20 ms\"}\n", kConfigs / "benches", "t.yaml")
          .can.quick_stop_timeout_s,
      0.02);
  EXPECT_DOUBLE_EQ(
      parse_bench_config("can: {quick_stop_timeout: 0.1}\n", kConfigs / "benches", "t.yaml")
          .can.quick_stop_timeout_s,
      0.1);
  for (const char* bad : {"0", "\"-5 ms\"", "\"11 s\"", "\"5 N*m\"", "soon"}) {
    const auto e = parse_error(std::string("can: {quick_stop_timeout: ") + bad + "}\n");
    EXPECT_EQ(e.key(), "can.quick_stop_timeout") << bad;
  }
  const auto e = parse_error("can: {quick_stop_timeout: \"11 s\"}\n");
  EXPECT_NE(e.expected().find("(0, 10 s]"), std::string::npos) << e.expected();
}

// Node guarding (issue 20): can.node_guarding with defaults 100 ms x 3 and no forced nodes;
// simbench's heartbeat_producer switch passes through simulated.simbench.
TEST(BenchConfig, NodeGuardingKeys) {
  const auto defaults = default_simulated_bench_config().can.node_guarding;
  EXPECT_DOUBLE_EQ(defaults.guard_time_s, 0.1);
  EXPECT_EQ(defaults.life_time_factor, 3);
  EXPECT_TRUE(defaults.nodes.empty());
  const auto c = parse_bench_config(
      "can: {node_guarding: {guard_time: \"50 ms\", life_time_factor: 4, nodes: [1, 4]}}\n"
      "simulated: {simbench: {drive: {heartbeat_producer: false}}}\n",
      kConfigs / "benches", "t.yaml");
  EXPECT_DOUBLE_EQ(c.can.node_guarding.guard_time_s, 0.05);
  EXPECT_EQ(c.can.node_guarding.life_time_factor, 4);
  EXPECT_EQ(c.can.node_guarding.nodes, (std::vector<std::uint8_t>{1, 4}));
  ASSERT_TRUE(c.simulated && c.simulated->devices);
  EXPECT_FALSE(c.simulated->devices->drive.identity.heartbeat_producer);

  auto e = parse_error("can: {node_guarding: {guard_time: \"0 ms\"}}\n");
  EXPECT_EQ(e.key(), "can.node_guarding.guard_time");
  e = parse_error("can: {node_guarding: {life_time_factor: 0}}\n");
  EXPECT_EQ(e.key(), "can.node_guarding.life_time_factor");
  EXPECT_EQ(e.value(), "0");
  e = parse_error("can: {node_guarding: {nodes: [128]}}\n");
  EXPECT_EQ(e.key().rfind("can.node_guarding.nodes", 0), 0U) << e.key();
  e = parse_error("can: {node_guarding: {guard: 1}}\n");
  EXPECT_EQ(e.key(), "can.node_guarding.guard");
}

// EDS and identity keys (issue #9): the shipped configs name the simulated devices' EDS files;
// a missing or malformed EDS and bad identity values are errors naming the key.
TEST(BenchConfig, EdsAndIdentityKeys) {
  const auto c = default_simulated_bench_config();
  ASSERT_TRUE(c.drive.expect.eds);
  ASSERT_TRUE(c.encoder.expect.eds);
  ASSERT_TRUE(c.torque_sensor.expect.eds);
  EXPECT_EQ(c.drive.expect.eds_path.filename(), "servo_drive.eds");
  EXPECT_EQ(c.drive.expect.identity.vendor_id, 0xA57U);
  EXPECT_EQ(c.drive.expect.identity.product_code, 0x402U);
  EXPECT_FALSE(c.drive.expect.identity.serial_number);

  // torque_sensor.type from the EDS where the config is silent: 0x6130:1 is INTEGER32 there,
  // and the config's own type wins.
  auto t =
      parse_bench_config("torque_sensor: {eds: ../eds/torque_sensor.eds}\n", kConfigs / "benches");
  EXPECT_EQ(t.torque_sensor.sensor.type, canopen::ValueType::i32);
  t = parse_bench_config("torque_sensor: {eds: ../eds/torque_sensor.eds, type: f32}\n",
                         kConfigs / "benches");
  EXPECT_EQ(t.torque_sensor.sensor.type, canopen::ValueType::f32);

  auto e = parse_error("drive: {eds: ../eds/absent.eds}\n");
  EXPECT_EQ(e.key(), "drive.eds");
  EXPECT_NE(e.value().find("absent.eds"), std::string::npos) << e.value();
  // Not an EDS: the reader's message names the file and line.
  e = parse_error("encoder: {eds: sim.yaml}\n");
  EXPECT_EQ(e.key(), "encoder.eds");
  EXPECT_NE(e.expected().find("a CiA 306 EDS"), std::string::npos) << e.expected();
  e = parse_error("drive: {identity: {vendor: 1}}\n");
  EXPECT_EQ(e.key(), "drive.identity.vendor");
  e = parse_error("torque_sensor: {identity: {vendor_id: -1}}\n");
  EXPECT_EQ(e.key(), "torque_sensor.identity.vendor_id");
  e = parse_error("drive: {identity: {product_code: 0x1FFFFFFFF}}\n");
  EXPECT_EQ(e.key(), "drive.identity.product_code");
  e = parse_error("simulated: {brake_server: maybe}\n");
  EXPECT_EQ(e.key(), "simulated.brake_server");
}

// The simulated unit's truth is the twin's nominal case varied (TE x1.08 and +4 deg, stiffness
// x0.96, backlash 0.35 arcmin), and a variation in the config varies it further.
TEST(BenchConfig, TrueGearIsTheNominalCaseVaried) {
  const auto c = default_simulated_bench_config();
  const auto truth = true_gear_from(c);
  const auto& nominal = c.description.twin_gear;
  // The truth leads with a constant term (the encoders' zero misalignment, seed 004's mean TE
  // offset) that the nominal case does not know; the rest are the nominal terms varied.
  ASSERT_EQ(truth.te_terms.size(), nominal.te_terms.size() + 1);
  const auto& offset = truth.te_terms[0];
  EXPECT_EQ(offset.order_input, 0);
  EXPECT_EQ(offset.order_output, 0);
  EXPECT_NEAR(offset.amplitude_rad * std::sin(offset.phase_rad), 1.75 / 60 * M_PI / 180, 1e-12);
  for (std::size_t i = 0; i < nominal.te_terms.size(); ++i) {
    const auto& t = truth.te_terms[i + 1];
    EXPECT_NEAR(t.amplitude_rad, 1.08 * nominal.te_terms[i].amplitude_rad, 1e-12);
    EXPECT_NEAR(t.phase_rad - nominal.te_terms[i].phase_rad, 4 * M_PI / 180, 1e-12);
  }
  const auto& k_true = std::get<model::ThreeSegmentStiffness>(truth.stiffness.law);
  const auto& k_nominal = std::get<model::ThreeSegmentStiffness>(nominal.stiffness.law);
  EXPECT_NEAR(k_true.k1, 0.96 * k_nominal.k1, 1e-6);
  EXPECT_NEAR(k_true.k3, 0.96 * k_nominal.k3, 1e-6);
  EXPECT_NEAR(truth.backlash.total_rad, 0.35 / 60 * M_PI / 180, 1e-12);
  EXPECT_DOUBLE_EQ(truth.geometry.ratio, 100);

  const auto varied = parse_bench_config(
      "simulated: {true_gear: {case: sim-true-gear.yaml, stiffness_scale: 0.5, "
      "te_amplitude_scale: 2, backlash: \"1 arcmin\"}}\n",
      kConfigs / "benches", "t");
  const auto truth2 = true_gear_from(varied);
  EXPECT_NEAR(std::get<model::ThreeSegmentStiffness>(truth2.stiffness.law).k2, 0.5 * k_true.k2,
              1e-6);
  EXPECT_NEAR(truth2.te_terms[0].amplitude_rad, 2 * truth.te_terms[0].amplitude_rad, 1e-12);
  EXPECT_NEAR(truth2.backlash.total_rad, 1.0 / 60 * M_PI / 180, 1e-12);
}

TEST(BenchConfig, SafetyModbusTimeoutSetsTheLinkLossTimeout) {
  const auto c =
      parse_bench_config("safety: {modbus_link_timeout: \"250 ms\"}\n", kConfigs / "benches", "t");
  EXPECT_EQ(c.brake.link.link_loss_timeout, std::chrono::milliseconds(250));
}

}  // namespace
}  // namespace wavebench::bench
