// The simbench YAML section: values land in the device configs; bad values name key and value.
#include "wavebench/simdevices/simulated_bench_config.hpp"

#include <gtest/gtest.h>

namespace wavebench::simdevices {
namespace {

TEST(SimulatedBenchConfig, ReadsNodeIdsAndTorqueObject) {
  const auto c = parse_simulated_bench_config(R"(
simbench:
  clock: sync
  sync_period_us: 500
  drive: {node_id: 2, counts_per_revolution: 65536}
  encoder: {node_id: 5, resolution: 524288, revolutions: 4096, noise_arcsec: 0}
  torque_sensor: {node_id: 6, object: "0x7130:1", type: i16, scale: 0.01}
)");
  EXPECT_EQ(c.clock, BenchClock::kSyncDriven);
  EXPECT_DOUBLE_EQ(c.sync_period, 500e-6);
  EXPECT_EQ(c.drive.node_id, 2);
  EXPECT_EQ(c.drive.counts_per_revolution, 65536u);
  EXPECT_EQ(c.encoder.node_id, 5);
  EXPECT_EQ(c.encoder.single_turn_resolution, 524288u);
  EXPECT_EQ(c.encoder.revolutions, 4096);
  EXPECT_EQ(c.encoder.noise_rad, 0.0);
  EXPECT_EQ(c.torque_sensor.node_id, 6);
  EXPECT_EQ(c.torque_sensor.index, 0x7130);
  EXPECT_EQ(c.torque_sensor.sub, 1);
  EXPECT_EQ(c.torque_sensor.type, DataType::kInteger16);
  EXPECT_DOUBLE_EQ(c.torque_sensor.scale_nm_per_unit, 0.01);
}

TEST(SimulatedBenchConfig, DefaultsAreNodesOneThreeFour) {
  const auto c = parse_simulated_bench_config("other: 1\n");
  EXPECT_EQ(c.drive.node_id, 1);
  EXPECT_EQ(c.encoder.node_id, 3);
  EXPECT_EQ(c.torque_sensor.node_id, 4);
}

void expect_message(const std::string& yaml, const std::string& fragment) {
  try {
    parse_simulated_bench_config(yaml);
    FAIL() << "accepted: " << yaml;
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
  }
}

TEST(SimulatedBenchConfig, BadValuesNameKeyValueAndExpectation) {
  expect_message("simbench: {drive: {node_id: 200}}",
                 "simbench config: simbench.drive.node_id: got '200', expected");
  expect_message("simbench: {torque_sensor: {type: u8}}",
                 "simbench.torque_sensor.type: got 'u8', expected i16, i32 or f32");
  expect_message("simbench: {torque_sensor: {object: \"0x1000:1\"}}",
                 "simbench.torque_sensor.object");
  expect_message("simbench: {clock: fast}", "simbench.clock: got 'fast'");
  expect_message("simbench: {encoder: {node_id: 1}}", "three different node ids");
}

}  // namespace
}  // namespace wavebench::simdevices

namespace wavebench::simdevices {
namespace {

TEST(SimulatedBenchConfig, DriveUnitsFactorGroupAndAbsentObjects) {
  const auto c = parse_simulated_bench_config(R"(
simbench:
  drive:
    velocity_unit: factor_group
    factor_group: {gear_ratio: [3, 1], feed_constant: [360000, 1],
                   velocity_encoder_resolution: [4096, 1]}
    absent_objects: ["0x60F4", "0x6077"]
)");
  EXPECT_EQ(c.drive.velocity_unit, DriveVelocityUnit::kFactorGroup);
  EXPECT_EQ(c.drive.factor_group.gear_motor_revolutions, 3u);
  EXPECT_EQ(c.drive.factor_group.feed, 360000u);
  EXPECT_EQ(c.drive.factor_group.velocity_encoder_increments, 4096u);
  EXPECT_EQ(c.drive.factor_group.position_encoder_increments, 131072u);  // default
  EXPECT_FALSE(c.drive.has(0x60F4));
  EXPECT_FALSE(c.drive.has(0x6077));
  EXPECT_TRUE(c.drive.has(0x6064));
  EXPECT_EQ(parse_simulated_bench_config("simbench: {drive: {velocity_unit: \"0.1 rpm\"}}")
                .drive.velocity_unit,
            DriveVelocityUnit::kDeciRpm);
}

TEST(SimulatedBenchConfig, BadDriveUnitsNameKeyValueAndExpectation) {
  expect_message("simbench: {drive: {velocity_unit: rmp}}",
                 "simbench.drive.velocity_unit: got 'rmp', expected one of "
                 "counts/s|rpm|0.1 rpm|factor_group");
  expect_message("simbench: {drive: {absent_objects: [\"0x6064\"]}}",
                 "simbench.drive.absent_objects[0]: got '0x6064'");
  expect_message("simbench: {drive: {absent_objects: \"0x60F4\"}}",
                 "simbench.drive.absent_objects: got '0x60F4', expected a list");
  expect_message("simbench: {drive: {factor_group: {gear_ratio: [3]}}}",
                 "simbench.drive.factor_group.gear_ratio: got '[3]', expected [numerator, "
                 "denominator]");
  expect_message("simbench: {drive: {factor_group: {feed_constant: [-1, 1]}}}",
                 "simbench.drive.factor_group.feed_constant");
  expect_message("simbench: {drive: {factor_group: {feed: [1, 1]}}}",
                 "simbench.drive.factor_group.feed: got ");
}

}  // namespace
}  // namespace wavebench::simdevices
