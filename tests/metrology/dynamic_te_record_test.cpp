// The Welch average over every whole output revolution (revolution_welch.hpp) and the record's
// bounds (dynamic_te_record.hpp): a run longer than the order grid still averages all its
// revolutions, the worker thread gives what transforming in place gives, and the trace stays
// within the rows reserved for it however long the record runs.
#include "wavebench/metrology/dynamic_te_record.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>
#include <thread>
#include <vector>

#include "wavebench/metrology/revolution_welch.hpp"

namespace wavebench::metrology {
namespace {

constexpr double kPi = std::numbers::pi;

// Lines at output orders 3 and 40 (amplitudes 2 and 0.5) and a mean of 7.
double revolution_point(std::size_t j, std::size_t points) {
  const double x = 2 * kPi * static_cast<double>(j) / static_cast<double>(points);
  return 7 + 2 * std::sin(3 * x + 0.4) + 0.5 * std::sin(40 * x - 1.1);
}

void feed(RevolutionWelch& welch, std::size_t points, double revolutions, bool pause) {
  const auto total = static_cast<std::size_t>(revolutions * static_cast<double>(points));
  for (std::size_t i = 0; i < total; ++i) {
    welch.put(revolution_point(i % points, points));
    // A revolution lasts seconds on a bench; here the worker gets a few polls per revolution.
    if (pause && (i + 1) % points == 0) std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
}

TEST(RevolutionWelch, LinesReadTheirAmplitudeOverEveryWholeRevolution) {
  constexpr std::size_t kPoints = 1200;
  RevolutionWelch welch(kPoints, RevolutionWelch::Transform::kWherePut);
  feed(welch, kPoints, 10.5, false);
  const auto a = welch.finish();
  EXPECT_EQ(a.revolutions, 10U);  // the half revolution at the end is left out, not dropped
  EXPECT_EQ(a.dropped, 0U);
  EXPECT_DOUBLE_EQ(a.resolution, 1.0);
  ASSERT_GT(a.amplitude.size(), 40U);
  EXPECT_NEAR(a.amplitude[3], 2.0, 1e-9);
  EXPECT_NEAR(a.amplitude[40], 0.5, 1e-9);
  EXPECT_NEAR(a.amplitude[0], 0.0, 1e-9);  // the mean is removed
  // Hann leaks into the neighbours of a line only: a whole-order bin away from both is empty.
  EXPECT_NEAR(a.amplitude[20], 0.0, 1e-9);
}

TEST(RevolutionWelch, TheWorkerGivesWhatTransformingInPlaceGives) {
  constexpr std::size_t kPoints = 1200;
  RevolutionWelch in_place(kPoints, RevolutionWelch::Transform::kWherePut);
  RevolutionWelch worker(kPoints, RevolutionWelch::Transform::kOnWorker);
  feed(in_place, kPoints, 8.2, false);
  feed(worker, kPoints, 8.2, true);
  const auto a = in_place.finish();
  const auto b = worker.finish();
  EXPECT_EQ(b.revolutions, 8U);
  EXPECT_EQ(b.dropped, 0U);
  ASSERT_EQ(a.amplitude.size(), b.amplitude.size());
  for (std::size_t k = 0; k < a.amplitude.size(); ++k) {
    EXPECT_NEAR(a.amplitude[k], b.amplitude[k], 1e-12) << "bin " << k;
  }
}

TEST(RevolutionWelch, ARevolutionWithNoFreeBufferIsCountedNotLost) {
  // Fed far faster than a bench turns: the worker may fall behind its four buffers. Whatever it
  // took is averaged correctly, and what it could not take is counted.
  constexpr std::size_t kPoints = 64;
  RevolutionWelch welch(kPoints, RevolutionWelch::Transform::kOnWorker);
  feed(welch, kPoints, 200, false);
  const auto a = welch.finish();
  EXPECT_EQ(a.revolutions + a.dropped, 200U);
  ASSERT_GE(a.revolutions, 4U);  // the four buffers at least
  EXPECT_NEAR(a.amplitude[3], 2.0, 1e-9);
}

TEST(RevolutionWelch, FewerThanEightPointsAreRefused) {
  EXPECT_THROW(RevolutionWelch(7, RevolutionWelch::Transform::kWherePut), std::invalid_argument);
}

// 100 rpm input on N = 80 at 1 kHz: 48,000 samples per output revolution; 6.3 revolutions with
// lines at output orders 1 and 160 (the mesh).
TEST(DynamicTeRecord, WelchCoversRevolutionsPastTheGridAndTheTraceStaysInItsRows) {
  constexpr double kN = 80;
  constexpr double kArcsec = kPi / 180 / 3600;
  const double omega = 100.0 / 60 * 2 * kPi;
  const GearSense sense{kN, 1};
  DynamicTeRecordShape shape;
  shape.points_per_revolution = 48000;
  shape.max_revolutions = 2;  // the whole-record spectrum over the first two only
  shape.trace_stride = 1;
  shape.trace_capacity = 64;  // far fewer rows than blocks: the trace is merged as it goes
  DynamicTeRecord record(sense, shape);
  const auto n = static_cast<std::size_t>(6.3 * 48000);
  double lo = 1e300, hi = -1e300;
  for (std::size_t i = 0; i < n; ++i) {
    const double t = 1e-3 * static_cast<double>(i);
    const double theta1 = omega * t;
    const double theta2 = theta1 / kN;
    const double te = 3 + 4 * std::sin(theta2 + 0.3) + 1.5 * std::sin(160 * theta2 + 1.2);
    lo = std::min(lo, te);
    hi = std::max(hi, te);
    record.add_kept(t, theta1, theta2 + te * kArcsec);
  }
  const auto r = record.finish(GearTeeth{160, 162, 2}, {}, DynamicTeOptions{});
  EXPECT_EQ(r.order_revolutions, 2U);
  EXPECT_EQ(r.averaged_revolutions, 6U);
  EXPECT_EQ(r.averaged_revolutions_dropped, 0U);
  ASSERT_GT(r.averaged_amplitude_arcsec.size(), 160U);
  EXPECT_DOUBLE_EQ(r.averaged_order_output[160], 160.0);
  EXPECT_NEAR(r.averaged_amplitude_arcsec[1], 4.0, 4.0 * 1e-3);
  EXPECT_NEAR(r.averaged_amplitude_arcsec[160], 1.5, 1.5 * 1e-3);
  EXPECT_NEAR(r.p2p_arcsec, hi - lo, 1e-6);

  ASSERT_LE(r.te_arcsec.size(), 64U);
  EXPECT_GT(r.te_arcsec.size(), 16U);
  EXPECT_GT(r.trace_stride, 1U);
  EXPECT_EQ(r.trace_stride & (r.trace_stride - 1), 0U);  // doubled from 1
  // Min/max decimation keeps the record's extremes and time order.
  const auto [tmin, tmax] = std::minmax_element(r.te_arcsec.begin(), r.te_arcsec.end());
  EXPECT_NEAR(*tmin, lo, 1e-6);
  EXPECT_NEAR(*tmax, hi, 1e-6);
  EXPECT_TRUE(std::is_sorted(r.time_s.begin(), r.time_s.end()));
}

}  // namespace
}  // namespace wavebench::metrology
