#pragma once
// The TE spectrum of a record fed one sample at a time. A record of up to `segment` samples is
// transformed whole (metrology::spectrum_on_timestamps, every bin of the record); a longer one
// is averaged over segments of `segment` samples with half of each overlapping the next (Welch:
// the power of each bin averaged, so a steady line reads its amplitude), keeping one segment in
// memory however long the record.

#include <cstddef>
#include <optional>
#include <vector>

#include "wavebench/analysis/amplitude_spectrum.hpp"

namespace wavebench::report {

// A record longer than this is averaged rather than transformed whole: 2^18 samples (about four
// minutes at 1 kHz) keep a short run's spectrum as it was.
inline constexpr std::size_t kWholeRecordSpectrumSamples = std::size_t{1} << 18;

// Samples per segment for a record of `samples` at `sample_rate_hz` whose output turns at
// `output_hz`: 0 (the whole record) up to kWholeRecordSpectrumSamples, else whole output
// revolutions (two at least, and 4096 samples; at most kWholeRecordSpectrumSamples).
std::size_t spectrum_segment_samples(std::size_t samples, double sample_rate_hz, double output_hz);

class AveragedSpectrum {
 public:
  // segment 0: the whole record. Throws std::invalid_argument when 0 < segment < 16.
  AveragedSpectrum(std::size_t segment, analysis::SpectrumAnalyser& analyser);
  void add(double t, double value);
  // nullopt below 16 samples. With no full segment, the spectrum of what came (the whole
  // record); else the average of the full segments (a partial last one left out).
  std::optional<analysis::AmplitudeSpectrum> result() const;
  std::size_t segments() const { return segments_; }

 private:
  void analyse_segment();

  std::size_t segment_;
  analysis::SpectrumAnalyser& analyser_;
  std::vector<double> t_, v_;
  std::size_t segments_ = 0;
  std::vector<double> sum_frequency_, sum_power_;
  double sum_rate_ = 0, sum_resolution_ = 0;
};

}  // namespace wavebench::report
