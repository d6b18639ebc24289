#include "wavebench/metrology/settle_detector.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

namespace wavebench::metrology {
namespace {

SettleCriteria criteria() {
  SettleCriteria c;
  c.max_speed_rad_s = 1e-4;
  c.max_drift_rad = 2e-6;
  c.window_s = 0.2;
  c.max_settle_s = 3.0;
  return c;
}

TEST(SettleDetector, SettlesOneWindowAfterTheMotionDiesOut) {
  SettleDetector d(criteria());
  d.start(0.0);
  SettleState state = SettleState::kSettling;
  double t = 0;
  // Ringing until 0.5 s (speed 1e-2 rad/s), then still. Irregular 1 ms-ish steps.
  for (int i = 0; state == SettleState::kSettling && i < 10000; ++i) {
    t += (i % 3 == 0) ? 0.0013 : 0.0008;
    const bool moving = t < 0.5;
    const double theta = moving ? 1e-4 * std::sin(100 * t) : 1e-4 * std::sin(50.0);
    const double speed = moving ? 1e-2 * std::cos(100 * t) + 1e-2 : 0.0;
    state = d.add(t, theta, speed);
  }
  ASSERT_EQ(state, SettleState::kSettled);
  EXPECT_GE(d.settle_time_s(), 0.5 + 0.2 - 1e-9);
  EXPECT_LE(d.settle_time_s(), 0.5 + 0.2 + 0.003);
}

TEST(SettleDetector, SlowCreepUnderTheSpeedLimitStillTimesOutOnDrift) {
  SettleDetector d(criteria());
  d.start(10.0);
  SettleState state = SettleState::kSettling;
  double t = 10.0;
  while (state == SettleState::kSettling && t < 20) {
    t += 0.001;
    // 5e-5 rad/s: under the speed limit, but 1e-5 rad per 0.2 s window > 2e-6.
    state = d.add(t, 5e-5 * (t - 10.0), 5e-5);
  }
  EXPECT_EQ(state, SettleState::kTimedOut);
  EXPECT_NEAR(t, 13.0, 0.0015);
}

TEST(SettleDetector, RejectsNonPositiveCriteriaNamingTheKey) {
  auto c = criteria();
  c.window_s = 0;
  try {
    SettleDetector d(c);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("window_s"), std::string::npos);
  }
}

}  // namespace
}  // namespace wavebench::metrology
