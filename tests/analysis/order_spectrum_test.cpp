// Order spectrum: a line fixed to the shaft angle stays one sharp line while the speed ramps.
#include "wavebench/analysis/order_spectrum.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace wa = wavebench::analysis;

TEST(OrderSpectrum, ResamplesOnAngleExactlyForLinearData) {
  const std::vector<double> theta{0, 1, 3, 6};
  const std::vector<double> y{0, 2, 6, 12};  // y = 2 theta
  double step = 0;
  const auto r = wa::resample_on_angle(theta, y, 7, &step);
  EXPECT_DOUBLE_EQ(step, 1.0);
  for (std::size_t i = 0; i < r.size(); ++i) EXPECT_NEAR(r[i], 2.0 * i, 1e-12);
  const std::vector<double> stalled{0, 1, 1, 2};
  EXPECT_THROW(wa::resample_on_angle(stalled, y, 4, nullptr), std::invalid_argument);
}

TEST(OrderSpectrum, RampingSpeedGivesSharpOrderLines) {
  const double fs = 20000;
  const std::size_t n = 40000;  // 2 s
  std::vector<double> theta(n), y(n);
  const double ratio = 134;
  for (std::size_t i = 0; i < n; ++i) {
    const double t = static_cast<double>(i) / fs;
    theta[i] = 2 * std::numbers::pi * (20 * t + 10 * t * t);  // 20 Hz -> 60 Hz
    // Order 2 (housing) and order 5, fixed to the angle while the frequency triples.
    y[i] = 1.5 * std::sin(2 * theta[i]) + 0.5 * std::sin(5 * theta[i] + 0.4);
  }
  wa::SpectrumAnalyser analyser;
  const auto o = wa::order_spectrum(theta, y, ratio, wa::Window::kHann, {.max_peaks = 4}, analyser);
  // The record spans n - 1 sample intervals: 79.997 revolutions.
  EXPECT_NEAR(o.revolutions, 80.0, 0.01);
  EXPECT_NEAR(o.order_resolution, 1.0 / o.revolutions, 1e-12);
  ASSERT_GE(o.peaks.size(), 2u);
  EXPECT_NEAR(o.peaks[0].order_input, 2.0, 1e-3);
  EXPECT_NEAR(o.peaks[0].order_output, 268.0, 0.2);
  EXPECT_NEAR(o.peaks[0].amplitude, 1.5, 0.03);
  EXPECT_NEAR(o.peaks[1].order_input, 5.0, 1e-3);
  EXPECT_NEAR(o.peaks[1].amplitude, 0.5, 0.01);
  // The time spectrum of the same record smears the order-2 line over 40..120 Hz.
  const auto smeared = wa::amplitude_spectrum(y, fs, wa::Window::kHann);
  double largest = 0;
  for (double a : smeared.amplitude) largest = std::max(largest, a);
  EXPECT_LT(largest, 0.5);
}

TEST(OrderSpectrum, ResolvesTheTangentialLineWithEnoughRevolutions) {
  const double samples_per_rev = 64;
  const std::size_t n = 64 * 600;
  std::vector<double> theta(n), y(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double u = static_cast<double>(i) / samples_per_rev;
    theta[i] = 2 * std::numbers::pi * (u + 0.02 * u * u / 600);
    y[i] = std::sin(2 * theta[i]) + 0.5 * std::sin(2 * (1 + 1.0 / 134) * theta[i]);
  }
  wa::SpectrumAnalyser analyser;
  const auto o = wa::order_spectrum(theta, y, 134, wa::Window::kHann, {.max_peaks = 2}, analyser);
  ASSERT_EQ(o.peaks.size(), 2u);
  EXPECT_NEAR(o.peaks[0].order_input, 2.0, 2e-3);
  EXPECT_NEAR(o.peaks[1].order_input, 2 * (1 + 1.0 / 134), 2e-3);
  EXPECT_NEAR(o.peaks[1].order_output, 270.0, 0.3);
  EXPECT_NEAR(o.peaks[1].amplitude, 0.5, 0.02);
}
