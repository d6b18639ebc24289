#include "wavebench/analysis/spectral_peaks.hpp"

#include <algorithm>
#include <cmath>

namespace wavebench::analysis {
namespace {

// Offset d in [0, 0.5] of a line whose larger neighbour is on the + side: the neighbour-to-peak
// ratio of the window's lobe, lobe(1 - d) / lobe(d), rises monotonically with d; bisect it.
double offset_from_ratio(Window window, double ratio) {
  double lo = 0.0;
  double hi = 0.5;
  for (int i = 0; i < 60; ++i) {
    const double mid = 0.5 * (lo + hi);
    const double r = window_lobe(window, 1.0 - mid) / window_lobe(window, mid);
    (r < ratio ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

}  // namespace

std::vector<SpectralPeak> find_peaks(const AmplitudeSpectrum& spectrum, const PeakSearch& search) {
  const auto& a = spectrum.amplitude;
  std::vector<SpectralPeak> peaks;
  if (a.size() < 3) return peaks;
  const double max_f = search.max_frequency_hz > 0
                           ? search.max_frequency_hz
                           : static_cast<double>(a.size() - 1) * spectrum.resolution_hz;
  // Local maxima first; only the largest few are interpolated: a noisy floor holds tens of
  // thousands of maxima and each interpolation bisects the window's lobe.
  std::vector<std::size_t> maxima;
  for (std::size_t k = 1; k + 1 < a.size(); ++k) {
    const double f = static_cast<double>(k) * spectrum.resolution_hz;  // = frequency_hz[k]
    if (f > max_f || f < search.min_frequency_hz) continue;
    if (a[k] > a[k - 1] && a[k] >= a[k + 1]) maxima.push_back(k);
  }
  const std::size_t keep =
      search.max_peaks > 0
          ? std::max<std::size_t>(64, 4 * static_cast<std::size_t>(search.max_peaks))
          : maxima.size();
  if (maxima.size() > keep) {
    std::nth_element(maxima.begin(), maxima.begin() + static_cast<std::ptrdiff_t>(keep),
                     maxima.end(), [&](std::size_t x, std::size_t y) { return a[x] > a[y]; });
    maxima.resize(keep);
  }
  for (const std::size_t k : maxima) {
    SpectralPeak peak;
    peak.bin = static_cast<int>(k);
    const double left = a[k - 1];
    const double right = a[k + 1];
    double offset = 0;
    if (right > 0 || left > 0) {
      offset = right >= left ? offset_from_ratio(spectrum.window, right / a[k])
                             : -offset_from_ratio(spectrum.window, left / a[k]);
    }
    peak.bin_offset = offset;
    peak.frequency_hz = (static_cast<double>(k) + offset) * spectrum.resolution_hz;
    peak.amplitude = a[k] / window_lobe(spectrum.window, offset);
    peaks.push_back(peak);
  }
  std::sort(peaks.begin(), peaks.end(),
            [](const SpectralPeak& x, const SpectralPeak& y) { return x.amplitude > y.amplitude; });
  if (!peaks.empty()) {
    const double floor = peaks.front().amplitude * search.min_relative_amplitude;
    std::erase_if(peaks, [floor](const SpectralPeak& p) { return p.amplitude < floor; });
  }
  if (search.max_peaks > 0 && peaks.size() > static_cast<std::size_t>(search.max_peaks)) {
    peaks.resize(static_cast<std::size_t>(search.max_peaks));
  }
  return peaks;
}

}  // namespace wavebench::analysis
