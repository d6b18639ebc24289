#include "wavebench/analysis/twin_analysis.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "wavebench/analysis/signal_channel.hpp"
#include "wavebench/analysis/spectral_peaks.hpp"

namespace wavebench::analysis {
namespace {

std::string short_name(const std::string& source) {
  const auto bracket = source.find(" (");
  return bracket == std::string::npos ? source : source.substr(0, bracket);
}

// The TE term whose period strobes the section: the named one, else the one with the largest
// contribution to the analysed signal.
const model::TeTerm* strobe_term(const model::GearParams& params, const PoincareOptions& options,
                                 const LinearGearCoefficients* linear, const std::string& signal,
                                 double speed) {
  const auto& terms = params.te_terms;
  if (!options.excitation_source.empty()) {
    for (const auto& term : terms) {
      if (term.source == options.excitation_source ||
          short_name(term.source) == options.excitation_source) {
        return &term;
      }
    }
    std::string names;
    for (const auto& term : terms) names += (names.empty() ? "" : ", ") + short_name(term.source);
    throw std::invalid_argument("analysis.poincare.excitation_source = '" +
                                options.excitation_source + "': expected one of the TE terms (" +
                                names + ")");
  }
  const model::TeTerm* best = nullptr;
  double best_size = -1;
  for (const auto& term : terms) {
    if (term.amplitude_rad == 0 || (term.order_input == 0 && term.order_output == 0)) continue;
    double size = std::abs(term.amplitude_rad);
    if (linear) {
      const double f = model::te_term_frequency_hz(term, params.geometry, speed);
      size *= std::abs(te_transfer(*linear, signal, f));
    }
    if (size > best_size) {
      best_size = size;
      best = &term;
    }
  }
  return best;
}

// The angle-periodic stiffness variation excites the gear like a TE: at the operating twist x0
// the torque ripple k_p x0 cos(psi) equals the stiffness K-bar times an equivalent error
// e = (k_p x0 / K-bar) sin(psi + phi - pi/2) (the TE enters the twist with a minus sign).
std::vector<model::TeTerm> stiffness_variation_terms(const model::StiffnessParams& stiffness,
                                                     const LinearisedGear& gear) {
  std::vector<model::TeTerm> terms;
  const double x0 = gear.operating_twist_rad;
  const double torque = gear.operating_torque_nm;
  const double k = gear.coefficients.stiffness;
  auto add = [&](const model::StiffnessHarmonic& h, double ripple_torque) {
    if (ripple_torque == 0 || !(k > 0)) return;
    model::TeTerm t;
    t.source = "stiffness variation (" + std::to_string(static_cast<int>(h.order_input)) + "," +
               std::to_string(static_cast<int>(h.order_output)) + ")";
    t.family = model::TeFamily::kCustom;
    t.order_input = h.order_input;
    t.order_output = h.order_output;
    t.amplitude_rad = std::abs(ripple_torque) / k;
    t.phase_rad = h.phase_rad - 0.5 * std::numbers::pi + (ripple_torque < 0 ? std::numbers::pi : 0);
    terms.push_back(t);
  };
  if (const auto* lin = std::get_if<model::LinearPeriodicStiffness>(&stiffness.law)) {
    // x0 includes the backlash offset; the spring sees the filtered twist torque / k0.
    const double x = lin->k0 > 0 ? torque / lin->k0 : x0;
    for (const auto& h : lin->harmonics) add(h, h.amplitude * x);
  }
  for (const auto& h : stiffness.modulation) add(h, h.amplitude * torque);
  return terms;
}

double drive_frequency_hz(const model::GearParams& params) {
  if (const auto* dc = std::get_if<model::DcMotorInput>(&params.input)) {
    if (dc->voltage.amplitude != 0) return dc->voltage.frequency_hz;
  }
  if (const auto* tq = std::get_if<model::TorqueInput>(&params.input)) {
    if (tq->torque.amplitude != 0) return tq->torque.frequency_hz;
  }
  if (params.load.output_torque.amplitude != 0) return params.load.output_torque.frequency_hz;
  return 0;
}

}  // namespace

TwinAnalysis analyse_twin_run(const model::GearParams& params,
                              const model::SimulationOptions& sim_options,
                              const model::SimulationResult& result,
                              const AnalysisOptions& options) {
  TwinAnalysis out;
  const auto& r = result.response;
  out.signal = options.spectrum.signal;
  const auto y = response_channel(r, out.signal);
  if (y.size() < 16) {
    throw std::invalid_argument("analysis: the run returned " + std::to_string(y.size()) +
                                " samples of '" + out.signal +
                                "'; expected at least 16 (check t_end, transient, sample_rate)");
  }
  out.sample_rate_hz = r.t.size() >= 2
                           ? (static_cast<double>(r.t.size()) - 1) / (r.t.back() - r.t.front())
                           : sim_options.sample_rate;
  if (sim_options.sample_rate > 0 &&
      std::abs(out.sample_rate_hz - sim_options.sample_rate) < 1e-6 * sim_options.sample_rate) {
    out.sample_rate_hz = sim_options.sample_rate;
  }
  out.mean_input_speed = r.omega1.empty() ? params.nominal_input_speed : mean_of(r.omega1);
  out.rms = rms_about_mean(y);

  SpectrumAnalyser analyser;
  out.spectrum = analyser.analyse(y, out.sample_rate_hz, options.spectrum.window);
  PeakSearch search;
  search.max_peaks = options.spectrum.max_peaks;
  search.min_relative_amplitude = options.spectrum.min_relative_amplitude;
  search.max_frequency_hz = options.spectrum.max_frequency_hz;
  const auto peaks = find_peaks(out.spectrum, search);

  // The linear model is needed for attribution even when its report is not asked for.
  std::optional<LinearisedGear> linear;
  try {
    linear = linearise_gear(params, r.gear_torque.empty() ? 0.0 : mean_of(r.gear_torque));
  } catch (const std::invalid_argument&) {
    linear.reset();  // e.g. a stiffness law without a usable tangent: attribute by amplitude
  }
  if (options.linearise) out.linear = linear;

  AttributionInput attribution;
  attribution.terms = params.te_terms;
  if (linear) {
    const auto ripple = stiffness_variation_terms(params.stiffness, *linear);
    attribution.terms.insert(attribution.terms.end(), ripple.begin(), ripple.end());
  }
  attribution.geometry = params.geometry;
  attribution.mean_input_speed = out.mean_input_speed;
  attribution.sample_rate_hz = out.sample_rate_hz;
  attribution.resolution_hz = out.spectrum.resolution_hz;
  attribution.window = options.spectrum.window;
  attribution.signal = out.signal;
  attribution.use_transfer = linear.has_value() && has_te_transfer(out.signal);
  if (linear) attribution.linear = linear->coefficients;
  out.peaks = attribute_peaks(peaks, attribution);

  if (options.order_spectrum && r.theta1.size() == y.size()) {
    try {
      PeakSearch order_search = search;
      order_search.max_frequency_hz = 0;
      out.orders = order_spectrum(r.theta1, y, params.geometry.ratio, options.spectrum.window,
                                  order_search, analyser);
    } catch (const std::invalid_argument&) {
      out.orders.reset();  // the input stood still or reversed: no angle axis to resample on
    }
  }

  // Phase portrait, thinned for plotting; the section uses every sample.
  const std::size_t n = std::min(r.twist.size(), r.twist_rate.size());
  const std::size_t stride = std::max<std::size_t>(1, n / 50000);
  for (std::size_t i = 0; i < n; i += stride)
    out.portrait.points.push_back({r.twist[i], r.twist_rate[i]});

  const LinearGearCoefficients* co = linear ? &linear->coefficients : nullptr;
  const model::TeTerm* term =
      strobe_term(params, options.poincare, co, out.signal, out.mean_input_speed);
  // Without TE terms the drive's (or the load's) sinusoid is the excitation to strobe by; the
  // wave-generator revolution is the last resort.
  const double drive_hz = term ? 0.0 : drive_frequency_hz(params);
  if (n == r.t.size() && r.theta1.size() == n && r.te.size() == n) {
    const double a = term ? term->order_input : 1.0;
    const double b = term ? term->order_output : 0.0;
    std::vector<double> phase(n);
    for (std::size_t i = 0; i < n; ++i) {
      phase[i] = drive_hz > 0 ? 2 * std::numbers::pi * drive_hz * r.t[i]
                              : (a + b / params.geometry.ratio) * r.theta1[i] + b * r.te[i];
    }
    out.poincare = strobe_on_phase(r.t, phase, r.twist, r.twist_rate);
  }
  if (term) {
    out.poincare.excitation_source = term->source;
    out.poincare.excitation_frequency_hz =
        model::te_term_frequency_hz(*term, params.geometry, out.mean_input_speed);
  } else if (drive_hz > 0) {
    out.poincare.excitation_source = "drive/load sinusoid";
    out.poincare.excitation_frequency_hz = drive_hz;
  } else {
    out.poincare.excitation_source = "wave generator revolution";
    out.poincare.excitation_frequency_hz = out.mean_input_speed / (2 * std::numbers::pi);
  }
  // The first quarter of the section may still hold the transient's approach to the attractor.
  const auto& section = out.poincare.points;
  const std::size_t skip = section.size() >= 32 ? section.size() / 4 : 0;
  MotionClassifierOptions classifier;
  classifier.max_clusters = options.poincare.max_clusters;
  out.motion = classify_motion(std::span<const PhasePoint>(section).subspan(skip),
                               out.portrait.points, classifier);

  if (options.sweep.enabled) {
    out.sweep = run_speed_sweep(params, sim_options, options.sweep, out.signal, term);
  }
  if (options.sensitivity.enabled) {
    if (!linear || !has_te_transfer(out.signal)) {
      throw std::invalid_argument(
          "analysis.sensitivity needs a linearisable stiffness and a "
          "signal with a TE transfer function; signal = '" +
          out.signal + "'");
    }
    out.sensitivity = te_sensitivity(params, sim_options, options.sensitivity, out.signal,
                                     out.mean_input_speed, linear->coefficients, out.rms, true);
  }
  return out;
}

}  // namespace wavebench::analysis
