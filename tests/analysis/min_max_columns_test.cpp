#include "wavebench/analysis/min_max_columns.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

namespace wavebench::analysis {
namespace {

std::vector<double> times(std::size_t n, double dt) {
  std::vector<double> t(n);
  for (std::size_t i = 0; i < n; ++i) t[i] = static_cast<double>(i) * dt;
  return t;
}

TEST(MinMaxColumns, OneSampleSpikeSurvivesAtEveryColumnCount) {
  const auto t = times(100000, 1e-3);
  std::vector<double> y(t.size());
  for (std::size_t i = 0; i < y.size(); ++i) y[i] = std::sin(0.01 * static_cast<double>(i));
  y[54321] = 7.5;   // one sample, far outside the sine
  y[12345] = -6.0;  // and one below
  const std::vector<std::span<const double>> series{y};
  for (const std::size_t columns : {1u, 7u, 640u, 1920u, 4000u}) {
    const auto d = min_max_columns(t, series, 0.0, t.back(), columns);
    ASSERT_FALSE(d.full_resolution);
    EXPECT_LE(d.t.size(), 2 * columns);
    const auto [lo, hi] = std::minmax_element(d.series[0].begin(), d.series[0].end());
    EXPECT_EQ(*hi, 7.5) << columns << " columns";
    EXPECT_EQ(*lo, -6.0) << columns << " columns";
  }
}

TEST(MinMaxColumns, KeepsTheOrderInWhichMinAndMaxOccurred) {
  const std::vector<double> t{0, 1, 2, 3, 4, 5, 6, 7};
  const std::vector<double> rising{0, 1, 2, 3, 4, 5, 6, 7};
  const std::vector<double> falling{7, 6, 5, 4, 3, 2, 1, 0};
  const std::vector<std::span<const double>> series{rising, falling};
  const auto d = min_max_columns(t, series, 0, 8, 2);  // columns [0,4) and [4,8]
  ASSERT_EQ(d.t.size(), 4u);
  EXPECT_EQ(d.series[0], (std::vector<double>{0, 3, 4, 7}));
  EXPECT_EQ(d.series[1], (std::vector<double>{7, 4, 3, 0}));
  EXPECT_DOUBLE_EQ(d.t[0], 1.0);
  EXPECT_DOUBLE_EQ(d.t[3], 7.0);
}

TEST(MinMaxColumns, FewSamplesComeBackAtFullResolution) {
  const auto t = times(100, 0.01);
  std::vector<double> y(t.size(), 1.0);
  const std::vector<std::span<const double>> series{y};
  const auto d = min_max_columns(t, series, 0.2, 0.5, 200);
  EXPECT_TRUE(d.full_resolution);
  EXPECT_EQ(d.samples_in_range, d.t.size());
  EXPECT_GE(d.t.front(), 0.2);
  EXPECT_LE(d.t.back(), 0.5);
  EXPECT_EQ(d.t.size(), 31u);  // 0.20, 0.21, ..., 0.50 (within rounding of the grid)
}

TEST(MinMaxColumns, ColumnsWithoutFiniteValuesAreGaps) {
  const auto t = times(1000, 1.0);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::vector<double> y(t.size(), 2.0);
  std::fill(y.begin(), y.begin() + 500, nan);  // first half of the range missing
  const std::vector<std::span<const double>> series{y};
  const auto d = min_max_columns(t, series, 0, 999, 10);
  ASSERT_EQ(d.t.size(), 20u);
  EXPECT_TRUE(std::isnan(d.series[0][0]));
  EXPECT_EQ(d.series[0].back(), 2.0);
}

TEST(MinMaxColumns, RefusesMismatchedSeriesAndEmptyRanges) {
  const std::vector<double> t{0, 1, 2};
  const std::vector<double> short_series{1, 2};
  const std::vector<std::span<const double>> series{short_series};
  EXPECT_THROW(min_max_columns(t, series, 0, 2, 4), std::invalid_argument);
  const std::vector<std::span<const double>> none;
  EXPECT_THROW(min_max_columns(t, none, 2, 0, 4), std::invalid_argument);
  EXPECT_THROW(min_max_columns(t, none, 0, 2, 0), std::invalid_argument);
}

}  // namespace
}  // namespace wavebench::analysis
