#include "wavebench/report/axis_ticks.hpp"

#include <gtest/gtest.h>

namespace wavebench::report {
namespace {

TEST(AxisTicks, LinearTicksAreOneTwoFiveSteps) {
  const auto t = nice_ticks(0, 10, 6);
  ASSERT_EQ(t.size(), 6u);
  EXPECT_DOUBLE_EQ(t[1] - t[0], 2.0);
  const auto u = nice_ticks(-0.013, 0.047, 8);
  ASSERT_GE(u.size(), 4u);
  EXPECT_NEAR(u[1] - u[0], 0.01, 1e-15);
  EXPECT_GE(u.front(), -0.013);
  EXPECT_LE(u.back(), 0.047);
  EXPECT_EQ(u[1], 0.0);  // -0.01, 0, 0.01 ...: zero is exactly zero
}

TEST(AxisTicks, NiceRangeCoversTheDataAndHandlesFlatData) {
  const auto r = nice_range(0.3, 9.7);
  EXPECT_LE(r.lo, 0.3);
  EXPECT_GE(r.hi, 9.7);
  const auto flat = nice_range(5, 5);
  EXPECT_LT(flat.lo, 5);
  EXPECT_GT(flat.hi, 5);
}

TEST(AxisTicks, LogTicksAreDecades) {
  const auto t = log_ticks(1, 1e5);
  ASSERT_EQ(t.size(), 6u);
  EXPECT_DOUBLE_EQ(t[0], 1);
  EXPECT_DOUBLE_EQ(t[5], 1e5);
  const auto s = log_ticks(10, 100);  // one decade: 2 and 5 in between
  EXPECT_EQ(s.size(), 4u);
}

TEST(AxisTicks, LabelsShowTheDigitsTheStepNeeds) {
  EXPECT_EQ(tick_label(0.25, 0.25), "0.25");
  EXPECT_EQ(tick_label(2, 1), "2");
  EXPECT_EQ(tick_label(87.5, 2.5), "87.5");
  EXPECT_EQ(tick_label(90, 2.5), "90.0");
  EXPECT_EQ(tick_label(0.5, 0.1), "0.5");
  EXPECT_EQ(tick_label(1e5, 1e5), "1e+05");
}

}  // namespace
}  // namespace wavebench::report
