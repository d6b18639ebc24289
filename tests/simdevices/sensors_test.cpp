// CiA 406 encoder (resolution, multi-turn wrap, preset, code sequence, device type) and the
// configurable torque sensor process value.
#include <gtest/gtest.h>

#include <numbers>
#include <vector>

#include "wavebench/simdevices/output_encoder.hpp"
#include "wavebench/simdevices/sdo_abort.hpp"
#include "wavebench/simdevices/torque_sensor.hpp"

namespace wavebench::simdevices {
namespace {

EncoderConfig noiseless_encoder() {
  EncoderConfig c;
  c.noise_rad = 0;
  return c;
}

TEST(OutputEncoder, CountsPerTurnAndMultiTurnWrap) {
  Cia406Encoder enc(noiseless_encoder(), nullptr);
  EXPECT_EQ(enc.od().get<std::uint32_t>(0x1000, 0), 0x00020196u);
  EXPECT_EQ(enc.od().get<std::uint32_t>(0x6501, 0), 1u << 20);
  EXPECT_EQ(enc.od().get<std::uint16_t>(0x6502, 0), 2048u);
  enc.observe(2 * std::numbers::pi * 1.25);
  EXPECT_EQ(enc.position_value(), (1u << 20) + (1u << 18));
  // Just below zero wraps to the top of the 2048-turn range: floor(-166.9) = -167.
  enc.observe(-1e-3);
  const std::uint64_t total = (1ULL << 20) * 2048;
  EXPECT_EQ(enc.position_value(), total - 167);
}

TEST(OutputEncoder, PresetAndCodeSequence) {
  Cia406Encoder enc(noiseless_encoder(), nullptr);
  enc.observe(0.5);
  const std::vector<std::uint8_t> preset{0xE8, 0x03, 0x00, 0x00};  // 1000
  ASSERT_EQ(enc.od().write(0x6003, 0, preset), 0u);
  EXPECT_EQ(enc.position_value(), 1000u);
  enc.observe(0.5 + 2 * std::numbers::pi / (1 << 20) * 10.5);
  EXPECT_EQ(enc.position_value(), 1010u);
  const std::vector<std::uint8_t> down{0x01, 0x00};
  ASSERT_EQ(enc.od().write(0x6000, 0, down), 0u);
  enc.observe(0.5);
  const auto counted_down = enc.position_value();
  enc.observe(0.6);
  EXPECT_LT(enc.position_value(), counted_down);
  const std::vector<std::uint8_t> bad{0x04, 0x00};
  EXPECT_EQ(enc.od().write(0x6000, 0, bad), sdo_abort::kValueRange);
}

TEST(OutputEncoder, SingleTurnDeviceTypeAndRangeCheck) {
  EncoderConfig c = noiseless_encoder();
  c.revolutions = 1;
  Cia406Encoder single(c, nullptr);
  EXPECT_EQ(single.od().get<std::uint32_t>(0x1000, 0), 0x00010196u);
  single.observe(2 * std::numbers::pi * 3.5);
  EXPECT_EQ(single.position_value(), 1u << 19);
  c.revolutions = 8192;  // 2^20 * 2^13 does not fit 32 bits
  EXPECT_THROW(Cia406Encoder(c, nullptr), std::invalid_argument);
}

TEST(OutputEncoder, NoiseHasTheConfiguredSpread) {
  EncoderConfig c;
  c.noise_rad = 20 * 2 * std::numbers::pi / (1 << 20);  // 20 counts
  Cia406Encoder enc(c, nullptr);
  double sum = 0, sum2 = 0;
  const int n = 4000;
  for (int i = 0; i < n; ++i) {
    enc.observe(1.0);
    const double v = enc.position_value();
    sum += v;
    sum2 += v * v;
  }
  const double mean = sum / n;
  const double sd = std::sqrt(sum2 / n - mean * mean);
  EXPECT_NEAR(sd, 20, 2);
  EXPECT_NEAR(mean, 1.0 / (2 * std::numbers::pi) * (1 << 20), 2);
}

TEST(TorqueSensor, ProcessValueTypeIndexAndScaleFromConfig) {
  TorqueSensorConfig c;
  c.index = 0x7130;
  c.sub = 1;
  c.type = DataType::kInteger16;
  c.scale_nm_per_unit = 0.01;
  c.noise_nm = 0;
  TorqueSensor sensor(c, nullptr);
  sensor.observe(12.344);
  EXPECT_EQ(sensor.od().get<std::int16_t>(0x7130, 1), 1234);
  EXPECT_NEAR(sensor.value_nm(), 12.34, 1e-12);
  sensor.observe(-60);
  EXPECT_EQ(sensor.od().get<std::int16_t>(0x7130, 1), -6000);
  EXPECT_EQ(sensor.od().get<std::uint32_t>(0x1A00, 1), 0x71300110u);
  EXPECT_EQ(sensor.od().get<std::uint8_t>(0x7130, 0), 1u);
}

TEST(TorqueSensor, Real32ProcessValue) {
  TorqueSensorConfig c;
  c.type = DataType::kReal32;
  c.scale_nm_per_unit = 1;
  c.noise_nm = 0;
  TorqueSensor sensor(c, nullptr);
  sensor.observe(42.5);
  EXPECT_FLOAT_EQ(sensor.od().get<float>(0x6130, 1), 42.5f);
  EXPECT_EQ(sensor.od().get<std::uint32_t>(0x1A00, 1), 0x61300120u);
}

TEST(TorqueSensor, BadConfigNamesTheKey) {
  TorqueSensorConfig c;
  c.type = DataType::kVisibleString;
  try {
    TorqueSensor sensor(c, nullptr);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("type"), std::string::npos);
  }
  c = TorqueSensorConfig{};
  c.node_id = 0;
  try {
    TorqueSensor sensor(c, nullptr);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("node id 0"), std::string::npos);
  }
}

}  // namespace
}  // namespace wavebench::simdevices
