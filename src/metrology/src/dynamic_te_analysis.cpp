#include "wavebench/metrology/dynamic_te_analysis.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <stdexcept>

#include "wavebench/analysis/order_spectrum.hpp"
#include "wavebench/analysis/spectral_peaks.hpp"
#include "wavebench/metrology/dynamic_te_record.hpp"
#include "wavebench/metrology/figure_propagation.hpp"
#include "wavebench/metrology/revolution_welch.hpp"

namespace wavebench::metrology {

namespace {

constexpr double kTwoPi = 2 * std::numbers::pi;

struct OrderName {
  std::string name;
  double order_output;
};

std::vector<OrderName> order_names(const GearSense& sense, const GearTeeth& teeth,
                                   std::span<const PredictedComponent> predicted, int harmonics) {
  std::vector<OrderName> names;
  // The twin's own components first: when a line is both, the physical source says more.
  for (const auto& c : predicted) {
    names.push_back({c.name, c.order_input * sense.ratio + c.order_output});
  }
  for (int k = 1; k <= harmonics; ++k) {
    const std::string suffix = k == 1 ? "" : " x" + std::to_string(k);
    names.push_back({"output 1/rev" + suffix, static_cast<double>(k)});
    if (teeth.z_flex > 0) names.push_back({"mesh" + suffix, static_cast<double>(k * teeth.z_flex)});
  }
  // With z_C − z_F = U the mesh (z_F per output revolution) is also U per wave-generator
  // revolution; the line keeps the earlier name.
  const auto add_unless_named = [&names](std::string name, double order) {
    for (const auto& n : names) {
      if (std::abs(n.order_output - order) < 1e-9) return;
    }
    names.push_back({std::move(name), order});
  };
  add_unless_named("wave generator 1/rev", sense.ratio);
  add_unless_named("wave generator " + std::to_string(teeth.wave_number) + "/rev",
                   teeth.wave_number * sense.ratio);
  return names;
}

// The per-sample budget of a TE record [arcsec]: the encoders' steps, and the rest of the noise
// the second differences see (they see the quantisation too: it is taken out so that it is
// not counted twice).
UncertainFigure sample_budget(double measured_noise_arcsec, const GearSense& sense,
                              const DynamicTeOptions& o) {
  UncertainFigure f;
  const double q_out = quantisation_standard(o.output_resolution_rad) * kArcsecPerRad;
  const double q_in = quantisation_standard(o.input_resolution_rad / sense.ratio) * kArcsecPerRad;
  const double measured = measured_noise_arcsec;
  if (q_out > 0) f.add("output encoder quantisation", q_out, 'B', true);
  if (q_in > 0) f.add("input encoder quantisation (/N)", q_in, 'B', true);
  f.add("sample noise (second differences)",
        std::sqrt(std::max(0.0, measured * measured - q_out * q_out - q_in * q_in)), 'A', true);
  return f;
}

// Every source of `per_sample` times `factor`: a figure linear in the samples with
// Σ c_i² = factor².
UncertainFigure linear_figure(double value, const UncertainFigure& per_sample, double factor) {
  UncertainFigure f = scaled(per_sample, factor);
  f.value = value;
  return f;
}

struct RecordStatistics {
  double p2p = 0, rms = 0;
};

// p2p and RMS of `v` + `u`·(a normal draw) per point, without a perturbed copy.
template <class Noise>
RecordStatistics record_statistics(std::span<const double> v, Noise&& noise) {
  double sum = 0, squares = 0, lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const double x0 : v) {
    const double x = x0 + noise();
    sum += x;
    squares += x * x;
    lo = std::min(lo, x);
    hi = std::max(hi, x);
  }
  const double n = static_cast<double>(v.size());
  const double mean = sum / n;
  return {hi - lo, std::sqrt(std::max(0.0, squares / n - mean * mean))};
}

// p2p and RMS of a dense record: the linear terms (√2·u for p2p at its two extremes, u/√n for
// RMS), plus the Monte Carlo remainder (figure_propagation.hpp): with thousands of samples near
// each extreme the p2p's upward bias is a few u and must be in the budget. The draws perturb
// the record on its order grid (as dense as the samples): a long record keeps no other copy.
// Their bias is taken against the grid's own p2p and RMS.
void add_record_budgets(DynamicTeResult& r, std::span<const double> grid,
                        const UncertainFigure& per_sample, int draws) {
  const double n = static_cast<double>(r.samples);
  r.mean = linear_figure(r.mean_arcsec, per_sample, 1 / std::sqrt(n));
  r.p2p = linear_figure(r.p2p_arcsec, per_sample, std::sqrt(2.0));
  r.rms = linear_figure(r.rms_arcsec, per_sample, 1 / std::sqrt(n));
  const double u = per_sample.combined_standard();
  if (draws < 2 || !(u > 0) || grid.size() < 2) return;
  const auto exact = record_statistics(grid, [] { return 0.0; });
  std::mt19937_64 rng(PropagationOptions{}.seed);
  std::normal_distribution<double> unit(0.0, u);
  double p_sum = 0, p_ss = 0, r_sum = 0, r_ss = 0;
  for (int d = 0; d < draws; ++d) {
    const auto s = record_statistics(grid, [&] { return unit(rng); });
    p_sum += s.p2p;
    p_ss += s.p2p * s.p2p;
    r_sum += s.rms;
    r_ss += s.rms * s.rms;
  }
  const auto excess = [draws](double sum, double ss, double noiseless, const UncertainFigure& f) {
    const double m = sum / draws;
    const double var = std::max(0.0, (ss - draws * m * m) / (draws - 1));
    const double lin = f.combined_standard();
    return std::sqrt(std::max(0.0, var - lin * lin)) + std::abs(m - noiseless);
  };
  r.p2p.add(kExtremeSelectionSource, excess(p_sum, p_ss, exact.p2p, r.p2p), 'A', false);
  r.rms.add(kExtremeSelectionSource, excess(r_sum, r_ss, exact.rms, r.rms), 'A', false);
}

// Bins up to `max_order` (0: all) of a spectrum (bin k at k · resolution), with their axis.
void keep_orders(const std::vector<double>& amplitude, double resolution, double max_order,
                 std::vector<double>& axis_out, std::vector<double>& amplitude_out) {
  std::size_t end = amplitude.size();
  if (max_order > 0) {
    end = std::min(end, static_cast<std::size_t>(std::floor(max_order / resolution + 1e-9)) + 1);
  }
  axis_out.resize(end);
  for (std::size_t k = 0; k < end; ++k) axis_out[k] = static_cast<double>(k) * resolution;
  amplitude_out.assign(amplitude.begin(), amplitude.begin() + static_cast<std::ptrdiff_t>(end));
}

}  // namespace

double folded_frequency(double frequency_hz, double sample_rate_hz) {
  return std::abs(frequency_hz - sample_rate_hz * std::round(frequency_hz / sample_rate_hz));
}

analysis::AmplitudeSpectrum spectrum_on_timestamps(std::span<const double> time_s,
                                                   std::span<const double> signal,
                                                   analysis::Window window,
                                                   analysis::SpectrumAnalyser& analyser) {
  double step = 0;
  // n samples over n-1 mean periods; the closing point is dropped so the record spans whole
  // steps.
  auto uniform = analysis::resample_on_angle(time_s, signal, signal.size(), &step);
  uniform.pop_back();
  return analyser.analyse(uniform, 1.0 / step, window);
}

DynamicTeResult analyse_dynamic_record(const DynamicRecordFigures& figures,
                                       std::vector<double>&& grid,
                                       std::size_t points_per_revolution,
                                       const RevolutionAverage& averaged, const GearSense& sense,
                                       const GearTeeth& teeth,
                                       std::span<const PredictedComponent> predicted,
                                       const DynamicTeOptions& options) {
  sense.validate();
  DynamicTeResult r;
  r.samples = figures.samples;
  r.output_revolutions = figures.output_angle_rad / kTwoPi;
  if (r.output_revolutions < 1.0) {
    throw std::invalid_argument(
        "dynamic TE: output revolutions = " + std::to_string(r.output_revolutions) +
        "; expected at least one whole output revolution");
  }
  const std::size_t whole = grid.size() / points_per_revolution;
  if (whole < 1) {
    throw std::invalid_argument("dynamic TE: the order grid holds " + std::to_string(grid.size()) +
                                " points; expected at least one revolution of " +
                                std::to_string(points_per_revolution));
  }
  grid.resize(whole * points_per_revolution);
  const double duration = figures.duration_s;
  r.sample_rate_hz = static_cast<double>(figures.samples - 1) / duration;
  r.nyquist_hz = r.sample_rate_hz / 2;
  r.input_speed_hz = figures.input_angle_rad / kTwoPi / duration;
  r.mean_arcsec = figures.mean_arcsec;
  r.p2p_arcsec = figures.p2p_arcsec;
  r.rms_arcsec = figures.rms_arcsec;
  const UncertainFigure per_sample =
      sample_budget(figures.second_difference_noise_arcsec, sense, options);
  add_record_budgets(r, grid, per_sample, options.monte_carlo_draws);
  // Welch over every whole output revolution: each one's amplitude spectrum (Hann), the
  // amplitudes power-averaged (two revolutions at least).
  if (averaged.revolutions >= 2) {
    keep_orders(averaged.amplitude, averaged.resolution, options.max_order_kept,
                r.averaged_order_output, r.averaged_amplitude_arcsec);
    r.averaged_revolutions = averaged.revolutions;
  }
  r.averaged_revolutions_dropped = averaged.dropped;

  // Order spectrum over the whole output revolutions, so output orders fall on bins.
  const std::size_t grid_points = grid.size();
  r.order_points_per_revolution = points_per_revolution;
  r.order_revolutions = whole;
  const auto orders = analysis::amplitude_spectrum_in_place(
      std::move(grid), static_cast<double>(points_per_revolution), options.window);
  r.order_resolution = orders.resolution_hz;

  analysis::PeakSearch search;
  search.max_peaks = options.max_peaks;
  search.min_relative_amplitude = options.min_relative_amplitude;
  const double tolerance =
      options.name_tolerance > 0 ? options.name_tolerance : 1.5 * r.order_resolution;
  const auto names = order_names(sense, teeth, predicted, options.harmonics);
  const double output_hz = r.input_speed_hz / sense.ratio;
  for (const auto& p : analysis::find_peaks(orders, search)) {
    NamedPeak named;
    named.order_output = p.frequency_hz;
    named.order_input = p.frequency_hz / sense.ratio;
    named.frequency_hz = p.frequency_hz * output_hz;
    named.amplitude_arcsec = p.amplitude;
    // A line's amplitude in a Hann-windowed spectrum of n samples with white noise of standard
    // u per sample: u·√(2Σw²)/Σw = u·√(3/n) (Σw = n/2, Σw² = 3n/8).
    named.amplitude =
        linear_figure(p.amplitude, per_sample, std::sqrt(3.0 / static_cast<double>(grid_points)));
    named.name = "unnamed";
    double best = tolerance;
    for (const auto& candidate : names) {
      const double d = std::abs(candidate.order_output - p.frequency_hz);
      if (d < best || (d == best && named.name == "unnamed")) {  // ties: the first name
        best = d;
        named.name = candidate.name;
        if (d == 0) break;
      }
    }
    r.peaks.push_back(named);
  }
  keep_orders(orders.amplitude, orders.resolution_hz, options.max_order_kept, r.order_output,
              r.order_amplitude_arcsec);

  for (const auto& c : predicted) {
    const double f = std::abs(c.order_input + c.order_output / sense.ratio) * r.input_speed_hz;
    if (f > r.nyquist_hz) {
      r.aliased.push_back(
          {c.name, f, folded_frequency(f, r.sample_rate_hz), c.amplitude_rad * kArcsecPerRad});
    }
  }
  return r;
}

DynamicTeResult analyse_dynamic_te(std::span<const double> time_s,
                                   std::span<const double> theta_in_rad,
                                   std::span<const double> theta_out_rad, const GearSense& sense,
                                   const GearTeeth& teeth,
                                   std::span<const PredictedComponent> predicted,
                                   const DynamicTeOptions& options,
                                   analysis::SpectrumAnalyser& analyser) {
  sense.validate();
  const std::size_t n = time_s.size();
  if (theta_in_rad.size() != n || theta_out_rad.size() != n || n < 8) {
    throw std::invalid_argument("dynamic TE: time has " + std::to_string(n) + " samples, θ_in " +
                                std::to_string(theta_in_rad.size()) + ", θ_out " +
                                std::to_string(theta_out_rad.size()) +
                                "; expected equal lengths of at least 8");
  }
  // As many grid points per revolution as the record has samples (a 2·3·5-smooth count).
  const double turned = std::abs(sense.model_output_angle(theta_out_rad[n - 1]) -
                                 sense.model_output_angle(theta_out_rad[0])) /
                        kTwoPi;
  if (turned < 1.0) {
    throw std::invalid_argument("dynamic TE: output revolutions = " + std::to_string(turned) +
                                "; expected at least one whole output revolution");
  }
  DynamicTeRecordShape shape;
  shape.output_direction = theta_out_rad[n - 1] < theta_out_rad[0] ? -1.0 : 1.0;
  shape.points_per_revolution = smooth_size_at_least(std::max<std::size_t>(
      8, static_cast<std::size_t>(std::ceil(static_cast<double>(n - 1) / turned))));
  shape.max_revolutions = static_cast<std::size_t>(std::floor(turned));
  shape.trace_stride = 1;
  shape.trace_capacity = std::max<std::size_t>(n, 4);
  shape.welch_analyser = &analyser;
  DynamicTeRecord record(sense, shape);
  for (std::size_t i = 0; i < n; ++i) record.add_kept(time_s[i], theta_in_rad[i], theta_out_rad[i]);
  return record.finish(teeth, predicted, options);
}

nlohmann::json to_json(const DynamicTeResult& r) {
  nlohmann::json peaks = nlohmann::json::array();
  for (const auto& p : r.peaks) {
    peaks.push_back({{"name", p.name},
                     {"order_output", p.order_output},
                     {"order_input", p.order_input},
                     {"frequency_hz", p.frequency_hz},
                     {"amplitude_arcsec", p.amplitude_arcsec},
                     {"uncertainty", {{"amplitude_arcsec", to_json(p.amplitude)}}}});
  }
  nlohmann::json aliased = nlohmann::json::array();
  for (const auto& a : r.aliased) {
    aliased.push_back({{"name", a.name},
                       {"frequency_hz", a.frequency_hz},
                       {"folded_hz", a.folded_hz},
                       {"amplitude_arcsec", a.amplitude_arcsec}});
  }
  return {{"mean_arcsec", r.mean_arcsec},
          {"p2p_arcsec", r.p2p_arcsec},
          {"rms_arcsec", r.rms_arcsec},
          {"input_speed_hz", r.input_speed_hz},
          {"sample_rate_hz", r.sample_rate_hz},
          {"nyquist_hz", r.nyquist_hz},
          {"output_revolutions", r.output_revolutions},
          {"peaks", peaks},
          {"aliased", aliased},
          {"uncertainty",
           {{"mean_arcsec", to_json(r.mean)},
            {"p2p_arcsec", to_json(r.p2p)},
            {"rms_arcsec", to_json(r.rms)}}}};
}

}  // namespace wavebench::metrology
