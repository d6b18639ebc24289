// CiA 406 encoder and torque sensor clients, against the tests' own SDO server.
#include <gtest/gtest.h>

#include <numbers>

#include "fake_sdo_server.hpp"
#include "wavebench/canopen/cia406_encoder.hpp"
#include "wavebench/canopen/pdo.hpp"
#include "wavebench/canopen/torque_sensor.hpp"

namespace wavebench::canopen {
namespace {

struct DeviceFixture : ::testing::Test {
  boost::asio::io_context io;
  can::VirtualCanBus bus{io};
  std::unique_ptr<can::VirtualCanEndpoint> master = bus.endpoint("master");
  testing::FakeSdoServer server{bus, 3};
  SdoClient sdo{*master, 3, std::chrono::milliseconds(200)};
};

TEST(PositionUnwrapper, FollowsWrapsBothWays) {
  PositionUnwrapper u(4096);
  EXPECT_EQ(u.update(4000), 4000);
  EXPECT_EQ(u.update(10), 4096 + 10);
  EXPECT_EQ(u.update(4090), 4090);
  EXPECT_EQ(u.update(100), 4096 + 100);
  EXPECT_EQ(u.update(3000), 3000);  // -1196: motion, no wrap
  EXPECT_EQ(u.wraps(), 0);
  PositionUnwrapper full(0);
  full.update(0xFFFFFFF0U);
  EXPECT_EQ(full.update(0x10), (std::int64_t{1} << 32) + 0x10);
}

TEST_F(DeviceFixture, MultiTurnEncoderReadsResolutionAndUnwraps) {
  server.set<std::uint32_t>(0x1000, 0, kCia406MultiTurn);
  server.set<std::uint32_t>(0x6501, 0, 8192);
  server.set<std::uint16_t>(0x6502, 0, 16);
  server.set<std::uint32_t>(0x6004, 0, 8192 * 3 + 2048);
  Cia406Encoder enc(sdo);
  enc.read_configuration();
  EXPECT_TRUE(enc.multi_turn());
  EXPECT_EQ(enc.counts_per_turn(), 8192U);
  EXPECT_EQ(enc.turns(), 16U);
  EXPECT_NEAR(enc.read_angle(), 3.25 * 2 * std::numbers::pi, 1e-12);
  // Past the 16-turn range the raw value wraps; the angle keeps going.
  const std::uint32_t range = 8192 * 16;
  Cia406Encoder configured(sdo, Cia406Config{8192U, 16U});
  configured.on_position(range - 100);
  EXPECT_NEAR(configured.on_position(50), (range + 50) * 2 * std::numbers::pi / 8192, 1e-9);
}

TEST_F(DeviceFixture, SingleTurnEncoderWithConfiguredResolution) {
  server.set<std::uint32_t>(0x1000, 0, kCia406SingleTurn);
  Cia406Encoder enc(sdo, Cia406Config{1U << 17, std::nullopt});
  enc.read_configuration();
  EXPECT_FALSE(enc.multi_turn());
  EXPECT_EQ(enc.turns(), 1U);
  enc.on_position((1U << 17) - 1);
  EXPECT_NEAR(enc.on_position(1),
              (std::pow(2.0, 17) + 1) * 2 * std::numbers::pi / std::pow(2.0, 17), 1e-12);
}

TEST_F(DeviceFixture, EncoderWithoutResolutionObjectNamesIt) {
  server.set<std::uint32_t>(0x1000, 0, kCia406SingleTurn);
  Cia406Encoder enc(sdo);
  std::error_code ec;
  enc.read_configuration(ec);
  EXPECT_EQ(ec, make_error_code(SdoAbort::no_object));
  EXPECT_THROW(Cia406Encoder(sdo, Cia406Config{0U, std::nullopt}), std::invalid_argument);
}

TEST_F(DeviceFixture, TorqueSensorScalesItsConfiguredObject) {
  server.set<std::int16_t>(0x6130, 1, -1234);
  TorqueSensor sensor(sdo, TorqueSensorConfig{0x6130, 1, ValueType::i16, 0.01, 0.5});
  EXPECT_DOUBLE_EQ(sensor.read_torque(), -12.34 + 0.5);
  EXPECT_EQ(sensor.mapping_entry(), 0x61300110U);
  // The same value from a TPDO slot.
  PdoLayout layout({PdoEntry::decode(sensor.mapping_entry())});
  const std::uint64_t raw[] = {static_cast<std::uint16_t>(-1234)};
  const auto frame = layout.make_frame(0x184, raw);
  EXPECT_DOUBLE_EQ(sensor.torque_from_raw(layout.raw(frame, 0)), -12.34 + 0.5);
}

TEST_F(DeviceFixture, TorqueSensorFloatAndTypeMismatch) {
  server.set<float>(0x2000, 0, 2.5F);
  TorqueSensor f32(sdo, TorqueSensorConfig{0x2000, 0, ValueType::f32, 2.0, 0.0});
  EXPECT_DOUBLE_EQ(f32.read_torque(), 5.0);
  TorqueSensor wrong(sdo, TorqueSensorConfig{0x2000, 0, ValueType::i16, 1.0, 0.0});
  std::error_code ec;
  wrong.read_torque(ec);
  EXPECT_EQ(ec, make_error_code(SdoAbort::length_mismatch));
  EXPECT_THROW(TorqueSensor(sdo, TorqueSensorConfig{0x2000, 0, ValueType::i16, 0.0, 0.0}),
               std::invalid_argument);
}

}  // namespace
}  // namespace wavebench::canopen
