#pragma once
// One-sided amplitude spectrum with FFTW3. Scaling: a sine of amplitude A whose frequency lies
// on a bin reads A at that bin (whatever the window); the mean is removed first.

#include <cstddef>
#include <map>
#include <memory>
#include <span>
#include <vector>

#include "wavebench/analysis/analysis_options.hpp"

namespace wavebench::analysis {

struct AmplitudeSpectrum {
  std::vector<double> frequency_hz;  // bin k at k * resolution_hz, 0 .. fs/2
  std::vector<double> amplitude;     // same unit as the signal
  double sample_rate_hz = 0;
  double resolution_hz = 0;  // fs / N
  std::size_t samples = 0;   // N
  Window window = Window::kHann;
};

// Holds FFTW plans per length: a sweep or Monte-Carlo run transforms many records of the same
// length, and planning costs more than the transform. Not copyable (owns FFTW plans).
class SpectrumAnalyser {
 public:
  SpectrumAnalyser();
  ~SpectrumAnalyser();
  SpectrumAnalyser(const SpectrumAnalyser&) = delete;
  SpectrumAnalyser& operator=(const SpectrumAnalyser&) = delete;

  AmplitudeSpectrum analyse(std::span<const double> signal, double sample_rate_hz, Window window);
  std::size_t plans_created() const { return plans_created_; }

 private:
  struct Plan;
  std::map<std::size_t, std::unique_ptr<Plan>> plans_;
  std::size_t plans_created_ = 0;
};

// The same spectrum of a long record in the record's own memory (issue #12: a whole-record FFT
// holds one channel of doubles, not three): `signal` is windowed and transformed in place, and
// its storage becomes the result's amplitude. Its capacity should be size() + 2 (the r2c
// output's extra bin), else it grows once. `signal` is left empty. The result's frequency_hz
// is left empty too (another half channel): bin k is at k · resolution_hz.
AmplitudeSpectrum amplitude_spectrum_in_place(std::vector<double>&& signal, double sample_rate_hz,
                                              Window window);

// Convenience with a plan made for this call only.
AmplitudeSpectrum amplitude_spectrum(std::span<const double> signal, double sample_rate_hz,
                                     Window window);

}  // namespace wavebench::analysis
