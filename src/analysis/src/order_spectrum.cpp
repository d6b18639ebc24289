#include "wavebench/analysis/order_spectrum.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace wavebench::analysis {

std::vector<double> resample_on_angle(std::span<const double> theta, std::span<const double> signal,
                                      std::size_t points, double* angle_step) {
  if (theta.size() != signal.size() || theta.size() < 2 || points < 2) {
    throw std::invalid_argument("order spectrum: theta1 has " + std::to_string(theta.size()) +
                                " samples and the signal " + std::to_string(signal.size()) +
                                ", expected two equal lengths >= 2");
  }
  const double direction = theta.back() >= theta.front() ? 1.0 : -1.0;
  for (std::size_t i = 1; i < theta.size(); ++i) {
    if (!(direction * (theta[i] - theta[i - 1]) > 0)) {
      throw std::invalid_argument(
          "order spectrum: theta1 is not strictly monotone at sample " + std::to_string(i) +
          " (the wave generator stopped or reversed); expected a turning input");
    }
  }
  const double start = theta.front();
  const double step = (theta.back() - start) / static_cast<double>(points - 1);
  std::vector<double> out(points);
  std::size_t j = 0;
  for (std::size_t k = 0; k < points; ++k) {
    const double angle = k + 1 == points ? theta.back() : start + step * static_cast<double>(k);
    while (j + 2 < theta.size() && direction * (theta[j + 1] - angle) < 0) ++j;
    const double u = (angle - theta[j]) / (theta[j + 1] - theta[j]);
    out[k] = signal[j] + std::clamp(u, 0.0, 1.0) * (signal[j + 1] - signal[j]);
  }
  if (angle_step) *angle_step = std::abs(step);
  return out;
}

OrderSpectrum order_spectrum(std::span<const double> theta1, std::span<const double> signal,
                             double ratio, Window window, const PeakSearch& search,
                             SpectrumAnalyser& analyser) {
  double step = 0;
  // One point per time sample keeps the angular bandwidth close to the time-domain one; the
  // last point is dropped so the record spans whole steps, not a closed interval.
  auto resampled = resample_on_angle(theta1, signal, signal.size() + 1, &step);
  resampled.pop_back();
  const double samples_per_revolution = 2 * std::numbers::pi / step;
  const AmplitudeSpectrum s = analyser.analyse(resampled, samples_per_revolution, window);
  OrderSpectrum o;
  o.order_input = s.frequency_hz;
  o.amplitude = s.amplitude;
  o.order_resolution = s.resolution_hz;
  o.revolutions = static_cast<double>(resampled.size()) / samples_per_revolution;
  o.ratio = ratio;
  for (const auto& p : find_peaks(s, search)) {
    o.peaks.push_back({p.frequency_hz, p.frequency_hz * ratio, p.amplitude});
  }
  return o;
}

}  // namespace wavebench::analysis
