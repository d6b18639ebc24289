#include "wavebench/report/averaged_spectrum.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "wavebench/metrology/dynamic_te_analysis.hpp"

namespace wavebench::report {

std::size_t spectrum_segment_samples(std::size_t samples, double sample_rate_hz, double output_hz) {
  if (samples <= kWholeRecordSpectrumSamples) return 0;
  const double per_revolution = output_hz > 0 ? sample_rate_hz / output_hz : 0;
  if (!(per_revolution >= 1) || !std::isfinite(per_revolution)) {
    return kWholeRecordSpectrumSamples;
  }
  // Two revolutions at least so that neighbouring orders fall two bins apart, where a Hann
  // window's leakage from one does not reach the other.
  constexpr double kMinSegment = 4096;
  const double revolutions = std::max(2.0, std::ceil(kMinSegment / per_revolution));
  const double segment = std::round(revolutions * per_revolution);
  return static_cast<std::size_t>(
      std::min(segment, static_cast<double>(kWholeRecordSpectrumSamples)));
}

AveragedSpectrum::AveragedSpectrum(std::size_t segment, analysis::SpectrumAnalyser& analyser)
    : segment_(segment), analyser_(analyser) {
  if (segment != 0 && segment < 16) {
    throw std::invalid_argument("averaged spectrum: segment of " + std::to_string(segment) +
                                " samples; expected at least 16");
  }
}

void AveragedSpectrum::add(double t, double value) {
  t_.push_back(t);
  v_.push_back(value);
  if (segment_ == 0 || t_.size() < segment_) return;
  analyse_segment();
  // Half of the segment goes on into the next one (Hann windows overlapping by half weigh
  // every sample about equally).
  const auto keep = static_cast<std::ptrdiff_t>(segment_ / 2);
  t_.erase(t_.begin(), t_.end() - keep);
  v_.erase(v_.begin(), v_.end() - keep);
}

void AveragedSpectrum::analyse_segment() {
  const auto s = metrology::spectrum_on_timestamps(t_, v_, analysis::Window::kHann, analyser_);
  if (segments_ == 0) {
    sum_frequency_.assign(s.frequency_hz.size(), 0.0);
    sum_power_.assign(s.amplitude.size(), 0.0);
  }
  const std::size_t bins = std::min(sum_power_.size(), s.amplitude.size());
  for (std::size_t k = 0; k < bins; ++k) {
    sum_frequency_[k] += s.frequency_hz[k];
    sum_power_[k] += s.amplitude[k] * s.amplitude[k];
  }
  sum_rate_ += s.sample_rate_hz;
  sum_resolution_ += s.resolution_hz;
  ++segments_;
}

std::optional<analysis::AmplitudeSpectrum> AveragedSpectrum::result() const {
  if (segments_ == 0) {
    if (t_.size() < 16) return std::nullopt;
    return metrology::spectrum_on_timestamps(t_, v_, analysis::Window::kHann, analyser_);
  }
  analysis::AmplitudeSpectrum out;
  const double m = static_cast<double>(segments_);
  out.frequency_hz.resize(sum_frequency_.size());
  out.amplitude.resize(sum_power_.size());
  for (std::size_t k = 0; k < sum_power_.size(); ++k) {
    out.frequency_hz[k] = sum_frequency_[k] / m;
    out.amplitude[k] = std::sqrt(sum_power_[k] / m);
  }
  out.sample_rate_hz = sum_rate_ / m;
  out.resolution_hz = sum_resolution_ / m;
  out.samples = segment_;
  out.window = analysis::Window::kHann;
  return out;
}

}  // namespace wavebench::report
