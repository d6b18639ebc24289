#include "wavebench/procedures/dynamic_te_analysis.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <stdexcept>

#include "wavebench/analysis/order_spectrum.hpp"
#include "wavebench/analysis/spectral_peaks.hpp"
#include "wavebench/procedures/figure_propagation.hpp"

namespace wavebench::procedures {

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

void require_increasing(std::span<const double> v, const char* what) {
  for (std::size_t i = 1; i < v.size(); ++i) {
    if (!(v[i] > v[i - 1])) {
      throw std::invalid_argument(std::string("dynamic TE: ") + what +
                                  " is not strictly increasing at sample " + std::to_string(i) +
                                  "; expected a turning gear and increasing timestamps");
    }
  }
}

// The per-sample budget of a TE record [arcsec]: the encoders' steps, and the rest of the noise
// the second differences see (they see the quantisation too: it is taken out so that it is
// not counted twice).
UncertainFigure sample_budget(std::span<const double> te_arcsec, const GearSense& sense,
                              const DynamicTeOptions& o) {
  UncertainFigure f;
  const double q_out = quantisation_standard(o.output_resolution_rad) * kArcsecPerRad;
  const double q_in = quantisation_standard(o.input_resolution_rad / sense.ratio) * kArcsecPerRad;
  const double measured = sample_noise_from_second_differences(te_arcsec);
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

RecordStatistics record_statistics(std::span<const double> v) {
  double sum = 0, lo = INFINITY, hi = -INFINITY;
  for (double x : v) {
    sum += x;
    lo = std::min(lo, x);
    hi = std::max(hi, x);
  }
  const double mean = sum / static_cast<double>(v.size());
  double ss = 0;
  for (double x : v) ss += (x - mean) * (x - mean);
  return {hi - lo, std::sqrt(ss / static_cast<double>(v.size()))};
}

// p2p and RMS of a dense record: the linear terms (√2·u for p2p at its two extremes, u/√n for
// RMS), plus the Monte Carlo remainder (figure_propagation.hpp): with thousands of samples near
// each extreme the p2p's upward bias is a few u and must be in the budget.
void add_record_budgets(DynamicTeResult& r, const UncertainFigure& per_sample, int draws) {
  const double n = static_cast<double>(r.te_arcsec.size());
  r.mean = linear_figure(r.mean_arcsec, per_sample, 1 / std::sqrt(n));
  r.p2p = linear_figure(r.p2p_arcsec, per_sample, std::sqrt(2.0));
  r.rms = linear_figure(r.rms_arcsec, per_sample, 1 / std::sqrt(n));
  const double u = per_sample.combined_standard();
  if (draws < 2 || !(u > 0)) return;
  std::mt19937_64 rng(PropagationOptions{}.seed);
  std::normal_distribution<double> unit(0.0, u);
  std::vector<double> perturbed(r.te_arcsec.size());
  double p_sum = 0, p_ss = 0, r_sum = 0, r_ss = 0;
  for (int d = 0; d < draws; ++d) {
    for (std::size_t i = 0; i < perturbed.size(); ++i) perturbed[i] = r.te_arcsec[i] + unit(rng);
    const auto s = record_statistics(perturbed);
    p_sum += s.p2p;
    p_ss += s.p2p * s.p2p;
    r_sum += s.rms;
    r_ss += s.rms * s.rms;
  }
  const auto excess = [draws](double sum, double ss, const UncertainFigure& f) {
    const double m = sum / draws;
    const double var = std::max(0.0, (ss - draws * m * m) / (draws - 1));
    const double lin = f.combined_standard();
    return std::sqrt(std::max(0.0, var - lin * lin)) + std::abs(m - f.value);
  };
  r.p2p.add(kExtremeSelectionSource, excess(p_sum, p_ss, r.p2p), 'A', false);
  r.rms.add(kExtremeSelectionSource, excess(r_sum, r_ss, r.rms), 'A', false);
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
  require_increasing(time_s, "time");
  DynamicTeResult r;
  r.time_s.resize(n);
  r.output_angle_rad.resize(n);
  r.te_arcsec.resize(n);
  const double theta2_0 = sense.model_output_angle(theta_out_rad[0]);
  for (std::size_t i = 0; i < n; ++i) {
    r.time_s[i] = time_s[i] - time_s[0];
    r.output_angle_rad[i] = sense.model_output_angle(theta_out_rad[i]) - theta2_0;
    r.te_arcsec[i] = sense.transmission_error(theta_in_rad[i], theta_out_rad[i]) * kArcsecPerRad;
  }
  // Order analysis needs the output turning one way; reversed, run it on −θ2.
  const bool reversed = r.output_angle_rad.back() < 0;
  std::vector<double> angle = r.output_angle_rad;
  if (reversed) {
    for (auto& a : angle) a = -a;
  }
  require_increasing(angle, "output angle");
  r.output_revolutions = angle.back() / kTwoPi;
  if (r.output_revolutions < 1.0) {
    throw std::invalid_argument(
        "dynamic TE: output revolutions = " + std::to_string(r.output_revolutions) +
        "; expected at least one whole output revolution");
  }
  const double duration = r.time_s.back();
  r.sample_rate_hz = static_cast<double>(n - 1) / duration;
  r.nyquist_hz = r.sample_rate_hz / 2;
  r.input_speed_hz = std::abs(theta_in_rad[n - 1] - theta_in_rad[0]) / kTwoPi / duration;

  double sum = 0, lo = INFINITY, hi = -INFINITY;
  for (double v : r.te_arcsec) {
    sum += v;
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  r.mean_arcsec = sum / static_cast<double>(n);
  r.p2p_arcsec = hi - lo;
  double squares = 0;
  for (double v : r.te_arcsec) squares += (v - r.mean_arcsec) * (v - r.mean_arcsec);
  r.rms_arcsec = std::sqrt(squares / static_cast<double>(n));
  const UncertainFigure per_sample = sample_budget(r.te_arcsec, sense, options);
  add_record_budgets(r, per_sample, options.monte_carlo_draws);

  r.spectrum_hz = spectrum_on_timestamps(r.time_s, r.te_arcsec, options.window, analyser);

  // Order spectrum over the whole output revolutions only, so output orders fall on bins.
  const double whole_revs = std::floor(r.output_revolutions);
  const double end_angle = whole_revs * kTwoPi;
  std::size_t last = 0;
  while (last + 1 < n && angle[last + 1] <= end_angle) ++last;
  std::vector<double> a(angle.begin(), angle.begin() + static_cast<std::ptrdiff_t>(last + 1));
  std::vector<double> te(r.te_arcsec.begin(),
                         r.te_arcsec.begin() + static_cast<std::ptrdiff_t>(last + 1));
  if (last + 1 < n && a.back() < end_angle) {  // close the span exactly at whole revolutions
    const double u = (end_angle - angle[last]) / (angle[last + 1] - angle[last]);
    a.push_back(end_angle);
    te.push_back(r.te_arcsec[last] + u * (r.te_arcsec[last + 1] - r.te_arcsec[last]));
  }
  double step = 0;
  auto resampled = analysis::resample_on_angle(a, te, a.size(), &step);
  resampled.pop_back();
  const double points_per_rev = kTwoPi / step;
  const auto orders = analyser.analyse(resampled, points_per_rev, options.window);
  r.order_output = orders.frequency_hz;
  r.order_amplitude_arcsec = orders.amplitude;
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
    named.amplitude = linear_figure(p.amplitude, per_sample,
                                    std::sqrt(3.0 / static_cast<double>(resampled.size())));
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

  for (const auto& c : predicted) {
    const double f = std::abs(c.order_input + c.order_output / sense.ratio) * r.input_speed_hz;
    if (f > r.nyquist_hz) {
      r.aliased.push_back(
          {c.name, f, folded_frequency(f, r.sample_rate_hz), c.amplitude_rad * kArcsecPerRad});
    }
  }
  return r;
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

}  // namespace wavebench::procedures
