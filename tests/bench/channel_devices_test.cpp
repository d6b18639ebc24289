// Channel devices (issue #9): a bench config with seed 004's input-side CiA 406 encoder as its
// own node records that channel, with no code that knows of it (configs/benches/
// sim-input-encoder.yaml), and bad `devices:` entries are refused naming the key.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "bench_test_support.hpp"
#include "wavebench/bench/canopen_bench.hpp"
#include "wavebench/config/config_error.hpp"

namespace wavebench::bench {
namespace {

using testing::kRpm;
using testing::SimBench;

const std::filesystem::path kConfigs = std::filesystem::path(WAVEBENCH_SOURCE_DIR) / "configs";

TEST(ChannelDevices, InputSideEncoderIsRecordedAsItsOwnChannel) {
  const auto config = load_bench_config(kConfigs / "benches" / "sim-input-encoder.yaml");
  ASSERT_EQ(config.devices.size(), 1u);
  SimBench sim(config);
  const auto channels = sim.bench->extra_channels();
  ASSERT_EQ(channels.size(), 1u);
  EXPECT_EQ(channels[0].name, "theta_in_encoder");
  EXPECT_EQ(channels[0].unit, "rad");
  sim.bench->connect();
  const double theta0 = sim.bench->latest_sample().theta_in_rad;
  sim.bench->move_input_to(theta0 + 3.5 * 2 * std::numbers::pi, 600 * kRpm);  // wraps 3 times
  sim.bench->disconnect();

  // Every cycle's sample carries the encoder, and it follows the drive's own motor position
  // (both read the same shaft) within a drive count (2 pi / 131072 = 48 urad) plus the
  // encoder's noise, across the encoder's own wraps.
  const auto& samples = sim.observer.samples;
  ASSERT_GT(samples.size(), 500u);
  std::size_t with_both = 0;
  double offset = 0, worst = 0;
  for (const auto& s : samples) {
    EXPECT_TRUE(s.extra_arrived(0)) << s.index;
    if (!s.extra_arrived(0) || !s.valid(storage::kThetaInValid)) continue;
    const double d = s.extra[0] - s.theta_in_rad;
    if (with_both++ == 0) offset = d;
    worst = std::max(worst, std::abs(d - offset));
  }
  std::printf(
      "input encoder vs drive position over %zu samples: offset %.6f rad, worst %.1f urad\n",
      with_both, offset, worst * 1e6);
  EXPECT_EQ(with_both, samples.size());
  // The encoder's origin is its own single-turn zero: a whole number of turns from the drive's.
  EXPECT_NEAR(std::remainder(offset, 2 * std::numbers::pi), 0, 1e-4);
  EXPECT_LT(worst, 1e-4);
  EXPECT_GT(samples.back().extra[0] - samples.front().extra[0], 3 * 2 * std::numbers::pi);
}

TEST(ChannelDevices, BadDeviceEntriesAreRefusedNamingTheKey) {
  const auto refused = [](const std::string& devices) {
    try {
      parse_bench_config("devices:\n" + devices, kConfigs / "benches");
    } catch (const config::ConfigError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_NE(refused("  enc: {kind: cia406_encoder, node: 1}\n").find("devices.enc.node"),
            std::string::npos);  // the drive's node
  EXPECT_NE(refused("  enc: {kind: laser, node: 9}\n").find("cia406_encoder"), std::string::npos);
  EXPECT_NE(refused("  enc: {kind: cia406_encoder}\n").find("devices.enc.node"), std::string::npos);
  EXPECT_NE(refused("  torque: {kind: torque_sensor, node: 9}\n").find("devices"),
            std::string::npos);  // a core channel's name
  EXPECT_NE(refused("  Enc: {kind: cia406_encoder, node: 9}\n").find("[a-z0-9_]"),
            std::string::npos);
  EXPECT_NE(refused("  enc: {kind: cia406_encoder, node: 9, scale: 2}\n").find("devices.enc"),
            std::string::npos);  // a torque sensor's key on an encoder
  EXPECT_NE(refused("  enc: {kind: cia406_encoder, node: 9, sign: 0}\n").find("devices.enc.sign"),
            std::string::npos);
  EXPECT_EQ(refused("  t2: {kind: torque_sensor, node: 9, object: \"0x6130:2\", type: f32}\n"),
            "accepted");
}

}  // namespace
}  // namespace wavebench::bench
