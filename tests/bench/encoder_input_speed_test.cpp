// The input speed from the output encoder (issue #20): right over its window, robust to the
// encoder's quantisation and to a backlash jump, and the limit trips on it whatever 0x606C says.
#include "wavebench/bench/encoder_input_speed.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "wavebench/bench/safety_limits_check.hpp"

namespace wavebench::bench {
namespace {

constexpr double kRpm = 2 * std::numbers::pi / 60;  // rad/s per rpm
constexpr std::int64_t kMs = 1'000'000;
// A 2^20 counts/turn output encoder, truncated to its count.
double quantised(double theta) {
  const double step = 2 * std::numbers::pi / (1 << 20);
  return std::floor(theta / step) * step;
}

TEST(EncoderInputSpeed, MeasuresTheInputSpeedOverItsWindowThroughTheGear) {
  for (const int sign : {1, -1}) {
    EncoderInputSpeed speed({100, sign});
    const double input = 100 * kRpm;  // 1 rpm at the output
    std::optional<double> last;
    for (int k = 0; k < 50; ++k) {
      const double theta_out = sign * input / 100 * k * 1e-3;
      last = speed.add(k * kMs, quantised(theta_out));
      if (k < 8) {
        EXPECT_FALSE(last) << "no estimate before a whole window, k = " << k;
      }
    }
    ASSERT_TRUE(last);
    EXPECT_NEAR(*last, input, 1.0 * kRpm) << "quantisation noise over 8 ms stays below 1 rpm";
  }
}

TEST(EncoderInputSpeed, IgnoresRepeatedTimesAndRestartsWhenTimeGoesBack) {
  EncoderInputSpeed speed({100, 1});
  EXPECT_FALSE(speed.add(0, 0));
  EXPECT_FALSE(speed.add(0, 1));  // no time: no speed, not an infinite one
  for (int k = 1; k <= 8; ++k) speed.add(k * kMs, 0);
  EXPECT_TRUE(speed.add(9 * kMs, 0));
  EXPECT_FALSE(speed.add(2 * kMs, 5));  // back in time: a new window
}

TEST(EncoderInputSpeed, ABacklashJumpReadsFarBelowAnInputLimit) {
  // The output jumps 10 arcmin in one cycle with no input motion (lost motion reversal).
  EncoderInputSpeed speed({100, 1});
  double peak = 0;
  for (int k = 0; k < 40; ++k) {
    const double theta = k >= 20 ? 10.0 / model::kArcminPerRad : 0;
    if (const auto v = speed.add(k * kMs, quantised(theta))) peak = std::max(peak, std::abs(*v));
  }
  EXPECT_GT(peak, 0);
  EXPECT_LT(peak, 500 * kRpm) << "a limit of thousands of rpm never sees it";
}

TEST(SafetyLimitsCheck, TripsOnTheEncoderSpeedWhatever0x606CSays) {
  SafetyLimits l;
  l.max_input_speed_rad_s = 3000 * kRpm;
  SafetyLimitsCheck check(l, {100, -1});
  DriveCycleValues drive;
  // The input accelerates through 3000 rpm at 100 000 rpm/s while 0x606C reads 1/60 of it (a
  // drive in rpm read as counts/s would read far less still).
  const double accel = 100'000 * kRpm;
  double crossed_s = -1, tripped_s = -1;
  double theta_in = 0, omega = 0;
  for (int k = 0; k < 200 && tripped_s < 0; ++k) {
    const double t = k * 1e-3;
    omega = accel * t;
    theta_in = accel * t * t / 2;
    if (crossed_s < 0 && omega > l.max_input_speed_rad_s) crossed_s = t;
    storage::SyncSample s;
    s.flags = storage::kAllChannelsValid;
    s.receive_time_ns = k * kMs;
    s.theta_in_rad = theta_in;
    s.theta_out_rad = quantised(-theta_in / 100);
    s.input_speed_rad_s = omega / 60;
    if (const auto why = check.check(s, drive, {})) {
      tripped_s = t;
      EXPECT_NE(why->find("input speed measured by the output encoder"), std::string::npos) << *why;
      EXPECT_NE(why->find("beyond the limit 3000 rpm"), std::string::npos) << *why;
    }
  }
  ASSERT_GE(crossed_s, 0);
  ASSERT_GE(tripped_s, 0);
  EXPECT_LE(tripped_s - crossed_s, 0.1);
}

TEST(SafetyLimitsCheck, TheEncoderSpeedIsNotJudgedWithoutALimit) {
  SafetyLimitsCheck check({}, {100, 1});
  for (int k = 0; k < 20; ++k) {
    storage::SyncSample s;
    s.flags = storage::kThetaOutValid;
    s.receive_time_ns = k * kMs;
    s.theta_out_rad = k * 10.0;
    EXPECT_FALSE(check.check(s, {}, {}));
  }
}

}  // namespace
}  // namespace wavebench::bench
