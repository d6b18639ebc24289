// Amplitude spectrum and peak table against closed forms: a sine of amplitude A reads A.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <numeric>
#include <vector>

#include "wavebench/analysis/amplitude_spectrum.hpp"
#include "wavebench/analysis/spectral_peaks.hpp"
#include "wavebench/analysis/window.hpp"

namespace wa = wavebench::analysis;

namespace {

std::vector<double> tone(std::size_t n, double fs, double f, double a, double phase = 0.3,
                         double offset = 0) {
  std::vector<double> x(n);
  for (std::size_t i = 0; i < n; ++i) {
    x[i] = offset + a * std::sin(2 * std::numbers::pi * f * static_cast<double>(i) / fs + phase);
  }
  return x;
}

}  // namespace

TEST(Window, CoherentGainIsTheMeanCoefficient) {
  for (auto w : {wa::Window::kHann, wa::Window::kFlatTop, wa::Window::kRectangular}) {
    const auto c = wa::window_coefficients(w, 1024);
    const double mean = std::accumulate(c.begin(), c.end(), 0.0) / 1024.0;
    EXPECT_NEAR(mean, wa::coherent_gain(w), 1e-8) << wa::window_name(w);
  }
  const auto hann = wa::window_coefficients(wa::Window::kHann, 8);
  EXPECT_NEAR(hann[0], 0.0, 1e-15);  // periodic: zero at n = 0, one at n = N/2
  EXPECT_NEAR(hann[4], 1.0, 1e-15);
}

TEST(Window, LobeShapeMatchesClosedForms) {
  // Rectangular: |sinc(d)|; Hann at half a bin: 4/(3 pi) / 0.5 * ... = 0.8488 (-1.42 dB).
  EXPECT_NEAR(wa::window_lobe(wa::Window::kRectangular, 0.5), 2 / std::numbers::pi, 1e-12);
  EXPECT_NEAR(wa::window_lobe(wa::Window::kHann, 0.5), 8 / (3 * std::numbers::pi), 1e-12);
  EXPECT_NEAR(wa::window_lobe(wa::Window::kHann, 1.0), 0.5, 1e-12);
  EXPECT_NEAR(wa::window_lobe(wa::Window::kHann, 2.0), 0.0, 1e-12);
  // Flat-top scalloping loss is below 0.01 dB.
  EXPECT_NEAR(wa::window_lobe(wa::Window::kFlatTop, 0.5), 1.0, 1.2e-3);
}

TEST(AmplitudeSpectrum, OnBinSineReadsItsAmplitudeForEveryWindow) {
  const double fs = 1000;
  const std::size_t n = 1000;
  for (auto w : {wa::Window::kHann, wa::Window::kFlatTop, wa::Window::kRectangular}) {
    const auto s = wa::amplitude_spectrum(tone(n, fs, 50, 2.5, 0.3, 7.0), fs, w);
    EXPECT_DOUBLE_EQ(s.resolution_hz, 1.0);
    ASSERT_EQ(s.amplitude.size(), n / 2 + 1);
    EXPECT_NEAR(s.amplitude[50], 2.5, 1e-9) << wa::window_name(w);
    EXPECT_NEAR(s.amplitude[0], 0.0, 1e-9);  // mean removed
    EXPECT_DOUBLE_EQ(s.frequency_hz[50], 50.0);
  }
}

TEST(AmplitudeSpectrum, ReusesPlansPerLength) {
  wa::SpectrumAnalyser analyser;
  analyser.analyse(tone(512, 100, 10, 1), 100, wa::Window::kHann);
  analyser.analyse(tone(512, 100, 12, 1), 100, wa::Window::kFlatTop);
  analyser.analyse(tone(600, 100, 12, 1), 100, wa::Window::kHann);
  EXPECT_EQ(analyser.plans_created(), 2u);
}

TEST(AmplitudeSpectrum, RejectsTooShortSignals) {
  EXPECT_THROW(wa::amplitude_spectrum(std::vector<double>{1, 2}, 10, wa::Window::kHann),
               std::invalid_argument);
}

TEST(PeakTable, InterpolatesOffBinFrequencyAndAmplitude) {
  const double fs = 2048;
  const std::size_t n = 2048;  // 1 Hz bins
  for (double offset : {0.0, 0.13, 0.31, 0.5, 0.77}) {
    const double f = 200 + offset;
    for (auto w : {wa::Window::kHann, wa::Window::kFlatTop, wa::Window::kRectangular}) {
      const auto s = wa::amplitude_spectrum(tone(n, fs, f, 1.7), fs, w);
      const auto peaks = wa::find_peaks(s, {.max_peaks = 1});
      ASSERT_EQ(peaks.size(), 1u);
      const double df_tol = w == wa::Window::kFlatTop ? 0.05 : 0.01;
      EXPECT_NEAR(peaks[0].frequency_hz, f, df_tol) << wa::window_name(w) << " " << offset;
      EXPECT_NEAR(peaks[0].amplitude, 1.7, 1.7 * 2e-3) << wa::window_name(w) << " " << offset;
    }
  }
}

TEST(PeakTable, SortsByAmplitudeAndDropsSmallLines) {
  const double fs = 1000;
  const std::size_t n = 4000;
  auto x = tone(n, fs, 89.33, 1.0);
  const auto y = tone(n, fs, 44.667, 0.2, 1.0);
  const auto z = tone(n, fs, 300, 1e-6, 2.0);
  for (std::size_t i = 0; i < n; ++i) x[i] += y[i] + z[i];
  const auto s = wa::amplitude_spectrum(x, fs, wa::Window::kHann);
  const auto peaks = wa::find_peaks(s, {.max_peaks = 5, .min_relative_amplitude = 1e-3});
  ASSERT_EQ(peaks.size(), 2u);
  EXPECT_NEAR(peaks[0].frequency_hz, 89.33, 0.01);
  EXPECT_NEAR(peaks[1].frequency_hz, 44.667, 0.01);
  EXPECT_NEAR(peaks[1].amplitude, 0.2, 1e-3);
  const auto limited = wa::find_peaks(s, {.max_peaks = 5, .max_frequency_hz = 60});
  ASSERT_FALSE(limited.empty());
  EXPECT_NEAR(limited[0].frequency_hz, 44.667, 0.01);
}
