#include "wavebench/analysis/min_max_envelope.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <limits>
#include <span>
#include <stdexcept>
#include <vector>

#include "wavebench/analysis/min_max_columns.hpp"

namespace wavebench::analysis {
namespace {

// NaN compares unequal to itself: rows equal when both are NaN or both the same number.
void expect_same_rows(const DecimatedTrace& a, const DecimatedTrace& b) {
  EXPECT_EQ(a.full_resolution, b.full_resolution);
  EXPECT_EQ(a.samples_in_range, b.samples_in_range);
  ASSERT_EQ(a.t, b.t);
  ASSERT_EQ(a.series.size(), b.series.size());
  for (std::size_t k = 0; k < a.series.size(); ++k) {
    ASSERT_EQ(a.series[k].size(), b.series[k].size());
    for (std::size_t i = 0; i < a.series[k].size(); ++i) {
      const double x = a.series[k][i], y = b.series[k][i];
      if (std::isnan(x) || std::isnan(y)) {
        EXPECT_TRUE(std::isnan(x) && std::isnan(y)) << "series " << k << " row " << i;
      } else {
        EXPECT_EQ(x, y) << "series " << k << " row " << i;
      }
    }
  }
}

DecimatedTrace streamed(std::span<const double> t, const std::vector<std::vector<double>>& series,
                        double t0, double t1, std::size_t columns) {
  MinMaxEnvelope env(t0, t1, columns, series.size());
  std::vector<double> row(series.size());
  for (std::size_t i = 0; i < t.size(); ++i) {
    for (std::size_t k = 0; k < series.size(); ++k) row[k] = series[k][i];
    env.add(t[i], row);
  }
  return env.result();
}

DecimatedTrace whole(std::span<const double> t, const std::vector<std::vector<double>>& series,
                     double t0, double t1, std::size_t columns) {
  std::vector<std::span<const double>> spans(series.begin(), series.end());
  return min_max_columns(t, spans, t0, t1, columns);
}

// A record with jittered timestamps, a spike each way, NaN stretches and a constant series.
struct Record {
  std::vector<double> t;
  std::vector<std::vector<double>> series;
};

Record record(std::size_t n) {
  Record r;
  r.series.resize(3);
  double t = 0.25;
  for (std::size_t i = 0; i < n; ++i) {
    t += 1e-3 * (1 + 0.3 * std::sin(0.37 * static_cast<double>(i)));  // uneven periods
    r.t.push_back(t);
    const double x = static_cast<double>(i);
    r.series[0].push_back(std::sin(1e-3 * x) + 0.1 * std::sin(0.7 * x));
    r.series[1].push_back(i % 997 < 40 ? std::numeric_limits<double>::quiet_NaN() : x * 1e-3);
    r.series[2].push_back(2.0);  // ties everywhere: the first occurrence wins
  }
  if (n > 100) {
    r.series[0][n / 3] = 9.0;
    r.series[0][2 * n / 3] = -9.0;
  }
  return r;
}

TEST(MinMaxEnvelope, EqualsMinMaxColumnsOnTheWholeRecord) {
  const auto r = record(123457);
  for (const std::size_t columns : {1u, 3u, 640u, 1000u, 1920u}) {
    SCOPED_TRACE(columns);
    expect_same_rows(streamed(r.t, r.series, r.t.front(), r.t.back(), columns),
                     whole(r.t, r.series, r.t.front(), r.t.back(), columns));
    // A range inside the record: samples outside it are left out of both.
    const double a = r.t[1000], b = r.t[90000] + 1e-4;
    expect_same_rows(streamed(r.t, r.series, a, b, columns), whole(r.t, r.series, a, b, columns));
  }
}

TEST(MinMaxEnvelope, ShortRecordsComeBackAtFullResolutionAsMinMaxColumns) {
  for (const std::size_t n : {1u, 2u, 199u, 200u, 201u, 450u}) {
    SCOPED_TRACE(n);
    const auto r = record(n);
    const auto s = streamed(r.t, r.series, r.t.front(), r.t.back(), 100);
    expect_same_rows(s, whole(r.t, r.series, r.t.front(), r.t.back(), 100));
    EXPECT_EQ(s.full_resolution, n <= 200);
  }
}

TEST(MinMaxEnvelope, KeepsSpikesAndCountsWhatFellOutsideTheRange) {
  MinMaxEnvelope env(0, 10, 5, 1);
  for (int i = 0; i <= 1000; ++i) env.add(i * 0.01, i == 437 ? 50.0 : 1.0);
  env.add(-1, 99.0);  // outside: neither drawn nor counted in range
  env.add(std::numeric_limits<double>::quiet_NaN(), 99.0);
  EXPECT_EQ(env.samples_in_range(), 1001u);
  EXPECT_EQ(env.samples_outside_range(), 2u);
  const auto d = env.result();
  ASSERT_FALSE(d.full_resolution);
  // Five columns of 2 s, all holding samples; the spike at 4.37 s is the max of the third.
  ASSERT_EQ(d.t.size(), 10u);
  EXPECT_EQ(d.series[0], (std::vector<double>{1, 1, 1, 1, 1, 50, 1, 1, 1, 1}));
  EXPECT_DOUBLE_EQ(d.t[4], 4.5);
}

TEST(MinMaxEnvelope, RejectsBadRangesAndValueCounts) {
  EXPECT_THROW(MinMaxEnvelope(1, 0, 10, 1), std::invalid_argument);
  EXPECT_THROW(MinMaxEnvelope(0, 1, 0, 1), std::invalid_argument);
  EXPECT_THROW(MinMaxEnvelope(0, 1, 10, 0), std::invalid_argument);
  EXPECT_THROW(MinMaxEnvelope(0, std::numeric_limits<double>::infinity(), 10, 1),
               std::invalid_argument);
  MinMaxEnvelope env(0, 1, 10, 2);
  EXPECT_THROW(env.add(0.5, 1.0), std::invalid_argument);
}

}  // namespace
}  // namespace wavebench::analysis
