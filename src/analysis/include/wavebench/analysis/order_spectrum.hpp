#pragma once
// Order spectrum: the signal resampled on a uniform grid of the wave-generator angle, so lines
// tied to the shaft angles stay sharp when the speed varies.

#include <span>
#include <vector>

#include "wavebench/analysis/amplitude_spectrum.hpp"
#include "wavebench/analysis/spectral_peaks.hpp"

namespace wavebench::analysis {

struct OrderPeak {
  double order_input = 0;   // cycles per wave-generator revolution
  double order_output = 0;  // cycles per output revolution (order_input * N)
  double amplitude = 0;
};

struct OrderSpectrum {
  std::vector<double> order_input;  // bin axis in WG orders
  std::vector<double> amplitude;
  double order_resolution = 0;  // WG orders per bin (1 / revolutions recorded)
  double revolutions = 0;
  double ratio = 1;  // N, for output orders
  std::vector<OrderPeak> peaks;
};

// Linear interpolation of signal(theta) onto `points` uniform angles between the first and last
// theta. theta must be strictly monotone (either direction); throws std::invalid_argument.
std::vector<double> resample_on_angle(std::span<const double> theta, std::span<const double> signal,
                                      std::size_t points, double* angle_step);

OrderSpectrum order_spectrum(std::span<const double> theta1, std::span<const double> signal,
                             double ratio, Window window, const PeakSearch& search,
                             SpectrumAnalyser& analyser);

}  // namespace wavebench::analysis
