#include "wavebench/analysis/te_sensitivity.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <numbers>
#include <random>

#include "wavebench/analysis/signal_channel.hpp"

namespace wavebench::analysis {
namespace {

bool same_frequency(double a, double b) {
  return std::abs(a - b) <= 1e-9 * std::max({1.0, std::abs(a), std::abs(b)});
}

double percentile(std::vector<double> values, double q) {
  if (values.empty()) return 0;
  std::sort(values.begin(), values.end());
  const double pos = q * static_cast<double>(values.size() - 1);
  const auto i = static_cast<std::size_t>(pos);
  const double frac = pos - static_cast<double>(i);
  return i + 1 < values.size() ? values[i] + frac * (values[i + 1] - values[i]) : values[i];
}

}  // namespace

double linear_rms(const std::vector<model::TeTerm>& terms, const model::GearGeometry& geometry,
                  double mean_input_speed, const LinearGearCoefficients& linear,
                  const std::string& signal) {
  // Terms at one frequency add as phasors; different frequencies add in power.
  std::vector<std::pair<double, std::complex<double>>> lines;
  for (const auto& term : terms) {
    if (term.amplitude_rad == 0) continue;
    const double f = std::abs(model::te_term_frequency_hz(term, geometry, mean_input_speed));
    const auto c = te_transfer(linear, signal, f) * std::polar(term.amplitude_rad, term.phase_rad);
    auto it = std::find_if(lines.begin(), lines.end(),
                           [&](const auto& l) { return same_frequency(l.first, f); });
    if (it == lines.end()) {
      lines.emplace_back(f, c);
    } else {
      it->second += c;
    }
  }
  double power = 0;
  for (const auto& l : lines) power += l.first > 0 ? 0.5 * std::norm(l.second) : 0.0;
  return std::sqrt(power);
}

MonteCarloSummary monte_carlo_linear(const std::vector<model::TeTerm>& terms,
                                     const model::GearGeometry& geometry, double mean_input_speed,
                                     const LinearGearCoefficients& linear,
                                     const std::string& signal, int runs, unsigned seed) {
  MonteCarloSummary mc;
  mc.runs = runs;
  mc.seed = seed;
  mc.nominal = linear_rms(terms, geometry, mean_input_speed, linear, signal);
  if (runs <= 0) return mc;
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<double> values;
  values.reserve(static_cast<std::size_t>(runs));
  std::vector<model::TeTerm> sample = terms;
  for (int r = 0; r < runs; ++r) {
    for (std::size_t j = 0; j < terms.size(); ++j) {
      sample[j].amplitude_rad = terms[j].amplitude_rad * unit(rng);
      sample[j].phase_rad = 2 * std::numbers::pi * unit(rng);
    }
    values.push_back(linear_rms(sample, geometry, mean_input_speed, linear, signal));
  }
  double sum = 0, sum2 = 0;
  for (double v : values) {
    sum += v;
    sum2 += v * v;
  }
  mc.mean = sum / runs;
  mc.stddev = std::sqrt(std::max(0.0, sum2 / runs - mc.mean * mc.mean));
  mc.p50 = percentile(values, 0.5);
  mc.p95 = percentile(values, 0.95);
  mc.max = *std::max_element(values.begin(), values.end());
  return mc;
}

TeSensitivity te_sensitivity(const model::GearParams& params, const model::SimulationOptions& sim,
                             const SensitivityOptions& options, const std::string& signal,
                             double mean_input_speed, const LinearGearCoefficients& linear,
                             double rms_nominal, bool run_simulations) {
  TeSensitivity out;
  out.signal = signal;
  out.method = run_simulations ? "finite differences (one simulate per source) + linear"
                               : "linear transfer function";
  out.rms_nominal = rms_nominal;
  const auto& terms = params.te_terms;
  out.rms_linear = linear_rms(terms, params.geometry, mean_input_speed, linear, signal);
  const double h = options.relative_step > 0 ? options.relative_step : 0.1;
  for (std::size_t j = 0; j < terms.size(); ++j) {
    if (terms[j].amplitude_rad == 0) continue;
    SourceSensitivity s;
    s.source = terms[j].source;
    s.amplitude_rad = terms[j].amplitude_rad;
    s.frequency_hz = model::te_term_frequency_hz(terms[j], params.geometry, mean_input_speed);
    auto raised = terms;
    raised[j].amplitude_rad *= 1 + h;
    s.linear =
        (linear_rms(raised, params.geometry, mean_input_speed, linear, signal) - out.rms_linear) /
        h;
    s.finite_difference = std::numeric_limits<double>::quiet_NaN();
    if (run_simulations) {
      model::GearParams p = params;
      p.te_terms = raised;
      const auto result = model::simulate(p, sim);
      s.finite_difference =
          (rms_about_mean(response_channel(result.response, signal)) - rms_nominal) / h;
    }
    s.rank_value = run_simulations ? s.finite_difference : s.linear;
    out.sources.push_back(s);
  }
  std::sort(out.sources.begin(), out.sources.end(), [](const auto& a, const auto& b) {
    return std::abs(a.rank_value) > std::abs(b.rank_value);
  });
  out.monte_carlo = monte_carlo_linear(terms, params.geometry, mean_input_speed, linear, signal,
                                       options.monte_carlo_runs, options.seed);
  return out;
}

}  // namespace wavebench::analysis
