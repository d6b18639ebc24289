#include "wavebench/analysis/amplitude_spectrum.hpp"

#include <fftw3.h>

#include <cmath>
#include <mutex>
#include <numeric>
#include <stdexcept>
#include <string>

#include "wavebench/analysis/window.hpp"

namespace wavebench::analysis {
namespace {

// FFTW's planner is not thread-safe (fftw_execute is): the twin's diagnosis plans on its own
// thread while a procedure analyses on the bench's.
std::mutex& planner_mutex() {
  static std::mutex m;
  return m;
}

fftw_plan plan_r2c(std::size_t n, double* in, fftw_complex* out) {
  std::lock_guard lock(planner_mutex());
  return fftw_plan_dft_r2c_1d(static_cast<int>(n), in, out, FFTW_ESTIMATE);
}

void check_input(std::size_t n, double sample_rate_hz) {
  if (n < 4) {
    throw std::invalid_argument("spectrum: the signal has " + std::to_string(n) +
                                " samples, expected at least 4");
  }
  if (!(sample_rate_hz > 0)) {
    throw std::invalid_argument("spectrum: sample_rate " + std::to_string(sample_rate_hz) +
                                " Hz, expected > 0");
  }
}

}  // namespace

struct SpectrumAnalyser::Plan {
  explicit Plan(std::size_t n)
      : size(n),
        in(static_cast<double*>(fftw_malloc(sizeof(double) * n))),
        out(static_cast<fftw_complex*>(fftw_malloc(sizeof(fftw_complex) * (n / 2 + 1)))),
        plan(plan_r2c(n, in, out)) {
    if (plan == nullptr)
      throw std::runtime_error("FFTW could not plan a transform of " + std::to_string(n) +
                               " points");
  }
  ~Plan() {
    {
      std::lock_guard lock(planner_mutex());
      fftw_destroy_plan(plan);
    }
    fftw_free(in);
    fftw_free(out);
  }
  Plan(const Plan&) = delete;
  Plan& operator=(const Plan&) = delete;

  std::size_t size;
  double* in;
  fftw_complex* out;
  fftw_plan plan;
};

SpectrumAnalyser::SpectrumAnalyser() = default;
SpectrumAnalyser::~SpectrumAnalyser() = default;

AmplitudeSpectrum SpectrumAnalyser::analyse(std::span<const double> signal, double sample_rate_hz,
                                            Window window) {
  const std::size_t n = signal.size();
  check_input(n, sample_rate_hz);
  auto& slot = plans_[n];
  if (!slot) {
    slot = std::make_unique<Plan>(n);
    ++plans_created_;
  }
  Plan& plan = *slot;

  const auto w = window_coefficients(window, n);
  const double mean = std::accumulate(signal.begin(), signal.end(), 0.0) / static_cast<double>(n);
  double window_sum = 0;
  for (std::size_t i = 0; i < n; ++i) {
    plan.in[i] = (signal[i] - mean) * w[i];
    window_sum += w[i];
  }
  fftw_execute(plan.plan);

  AmplitudeSpectrum spectrum;
  spectrum.sample_rate_hz = sample_rate_hz;
  spectrum.samples = n;
  spectrum.resolution_hz = sample_rate_hz / static_cast<double>(n);
  spectrum.window = window;
  const std::size_t bins = n / 2 + 1;
  spectrum.frequency_hz.resize(bins);
  spectrum.amplitude.resize(bins);
  for (std::size_t k = 0; k < bins; ++k) {
    const double magnitude = std::hypot(plan.out[k][0], plan.out[k][1]);
    // One-sided: a line's power is split between +f and -f except at DC and Nyquist.
    const bool edge = k == 0 || (n % 2 == 0 && k == n / 2);
    spectrum.frequency_hz[k] = static_cast<double>(k) * spectrum.resolution_hz;
    spectrum.amplitude[k] = (edge ? 1.0 : 2.0) * magnitude / window_sum;
  }
  return spectrum;
}

AmplitudeSpectrum amplitude_spectrum_in_place(std::vector<double>&& signal, double sample_rate_hz,
                                              Window window) {
  std::vector<double> buffer = std::move(signal);
  signal.clear();
  const std::size_t n = buffer.size();
  check_input(n, sample_rate_hz);
  const std::size_t bins = n / 2 + 1;
  const double mean = std::accumulate(buffer.begin(), buffer.end(), 0.0) / static_cast<double>(n);
  // The window one coefficient at a time: its table would be another channel.
  double window_sum = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double w = window_coefficient(window, i, n);
    buffer[i] = (buffer[i] - mean) * w;
    window_sum += w;
  }
  buffer.resize(2 * bins);
  auto* complex = reinterpret_cast<fftw_complex*>(buffer.data());
  fftw_plan plan = nullptr;
  {
    std::lock_guard lock(planner_mutex());
    plan = fftw_plan_dft_r2c_1d(static_cast<int>(n), buffer.data(), complex,
                                FFTW_ESTIMATE | FFTW_UNALIGNED);
  }
  if (plan == nullptr) {
    throw std::runtime_error("FFTW could not plan a transform of " + std::to_string(n) + " points");
  }
  fftw_execute(plan);
  {
    std::lock_guard lock(planner_mutex());
    fftw_destroy_plan(plan);
  }
  AmplitudeSpectrum spectrum;
  spectrum.sample_rate_hz = sample_rate_hz;
  spectrum.samples = n;
  spectrum.resolution_hz = sample_rate_hz / static_cast<double>(n);
  spectrum.window = window;
  // Bin k's amplitude overwrites double k, which bin k has already been read from (k <= 2k).
  for (std::size_t k = 0; k < bins; ++k) {
    const double magnitude = std::hypot(buffer[2 * k], buffer[2 * k + 1]);
    const bool edge = k == 0 || (n % 2 == 0 && k == n / 2);
    buffer[k] = (edge ? 1.0 : 2.0) * magnitude / window_sum;
  }
  buffer.resize(bins);
  spectrum.amplitude = std::move(buffer);
  return spectrum;
}

AmplitudeSpectrum amplitude_spectrum(std::span<const double> signal, double sample_rate_hz,
                                     Window window) {
  SpectrumAnalyser analyser;
  return analyser.analyse(signal, sample_rate_hz, window);
}

}  // namespace wavebench::analysis
