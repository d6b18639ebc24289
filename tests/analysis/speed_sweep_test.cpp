// Speed sweep bookkeeping on synthetic data: speeds, the stepped kinematic trace, jumps and the
// hysteresis between the up and down sweeps.
#include "wavebench/analysis/speed_sweep.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace wa = wavebench::analysis;

namespace {

std::vector<wa::SweepPoint> points(const std::vector<double>& speeds,
                                   const std::vector<double>& amplitudes) {
  std::vector<wa::SweepPoint> p;
  for (std::size_t i = 0; i < speeds.size(); ++i) {
    wa::SweepPoint q;
    q.speed = speeds[i];
    q.amplitude = amplitudes[i];
    p.push_back(q);
  }
  return p;
}

}  // namespace

TEST(SpeedSweep, SpeedsAreEvenlySpacedAndValidated) {
  wavebench::analysis::SweepOptions o;
  o.from_speed = 10;
  o.to_speed = 50;
  o.steps = 5;
  o.record_time = 1;
  const auto s = wa::sweep_speeds(o);
  ASSERT_EQ(s.size(), 5u);
  EXPECT_DOUBLE_EQ(s[1], 20);
  EXPECT_DOUBLE_EQ(s[4], 50);
  o.steps = 1;
  EXPECT_THROW(wa::sweep_speeds(o), std::invalid_argument);
  o.steps = 3;
  o.to_speed = 5;
  EXPECT_THROW(wa::sweep_speeds(o), std::invalid_argument);
}

TEST(SpeedSweep, TraceHoldsEachSpeedAndIntegratesTheRamps) {
  double total = 0;
  const auto in = wa::sweep_trace({10, 20, 30}, 0.4, 1.0, 0.1, &total);
  EXPECT_NEAR(total, 3 * 1.4, 1e-12);
  ASSERT_EQ(in.trace_t.size(), in.trace_theta.size());
  for (std::size_t i = 1; i < in.trace_t.size(); ++i) ASSERT_GT(in.trace_t[i], in.trace_t[i - 1]);
  // Angle at the end: plateaus 10*1.4, then ramps 15*0.1 + 20*1.3, 25*0.1 + 30*1.3.
  EXPECT_NEAR(in.trace_theta.back(), 14 + 1.5 + 26 + 2.5 + 39, 1e-9);
  EXPECT_NEAR(in.trace_t.back(), total, 1e-12);
}

TEST(SpeedSweep, JumpsAboveTheThreshold) {
  const auto up = points({1, 2, 3, 4, 5}, {1.0, 1.1, 1.2, 3.0, 3.1});
  const auto jumps = wa::find_jumps(up, "up", 0.3);
  ASSERT_EQ(jumps.size(), 1u);
  EXPECT_DOUBLE_EQ(jumps[0].from_speed, 3);
  EXPECT_DOUBLE_EQ(jumps[0].to_speed, 4);
  EXPECT_NEAR(jumps[0].relative_change, 1.8 / 3.0, 1e-12);
}

TEST(SpeedSweep, HysteresisBetweenTheSweeps) {
  wa::SpeedSweep sweep;
  // Hardening Duffing-like: up stays on the upper branch to 4, down drops back at 2.
  sweep.up = points({1, 2, 3, 4, 5}, {1.0, 2.0, 3.0, 4.0, 0.5});
  sweep.down = points({5, 4, 3, 2, 1}, {0.5, 0.6, 0.7, 2.0, 1.0});
  wa::measure_hysteresis(sweep, 0.3);
  EXPECT_NEAR(sweep.max_hysteresis, 3.4 / 4.0, 1e-12);
  EXPECT_DOUBLE_EQ(sweep.hysteresis_speed, 4);
  ASSERT_EQ(sweep.hysteresis_speeds.size(), 2u);
  EXPECT_DOUBLE_EQ(sweep.hysteresis_speeds[0], 3);
  // Trapezoids of |up - down| = 0, 0, 2.3, 3.4, 0 over unit steps.
  EXPECT_NEAR(sweep.hysteresis_area, 0 + 1.15 + 2.85 + 1.7, 1e-12);
}
