#include "wavebench/twin/residual_watch.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>

#include "wavebench/analysis/order_spectrum.hpp"
#include "wavebench/analysis/peak_attribution.hpp"
#include "wavebench/config/twin_case_writer.hpp"
#include "wavebench/model/angle_units.hpp"
#include "wavebench/twin/twin_calibrator.hpp"

namespace wavebench::twin {
namespace {

constexpr double kTwoPi = 2 * std::numbers::pi;

double median(std::vector<double> v) {
  if (v.empty()) return 0;
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

// A term's order against the output revolution: (a + b/N) cycles per WG turn, N WG turns.
double output_order(const model::TeTerm& t, double ratio) {
  return std::abs(t.order_input * ratio + t.order_output);
}

double arcsec(double rad) {
  return rad / model::kRadPerArcsec;
}

// Turned at a steady speed: of 32 equal parts of the revolution, at most two (a start's ramp)
// took a time more than 25 % away from the median part's. A static or lost-motion run stops at
// every position: its record's own pattern (the stops) would fill the order spectrum.
bool steady(const std::vector<TwinPoint>& window, double start, double span) {
  constexpr int kParts = 32;
  std::vector<double> times;
  double boundary = span / kParts;
  double last_t = window.front().t_s;
  for (const auto& p : window) {
    if (std::abs(p.theta1_rad - start) >= boundary - 1e-12 * span) {
      times.push_back(p.t_s - last_t);
      last_t = p.t_s;
      boundary += span / kParts;
    }
  }
  if (times.size() < kParts / 2) return false;
  const double typical = median(times);
  int off = 0;
  for (double t : times) off += std::abs(t - typical) > 0.25 * typical ? 1 : 0;
  return off <= 2;
}

}  // namespace

std::string te_family_name(model::TeFamily family) {
  return config::te_family_name(family);
}

std::string suspect_for(const RankedSource& first) {
  static const std::pair<const char*, const char*> kSuspects[] = {
      {"tangential_output",
       "a local tooth defect on the Flexspline (or on a part turning with the output): it meshes "
       "U(N+1) times per output revolution"},
      {"tangential_fixed",
       "a local tooth defect on the fixed Circular Spline: it meshes U·N times per output "
       "revolution"},
      {"output_once_rev", "the output once-per-rev grew: a worn output bearing or flange"},
      {"output_assembly", "output-side assembly: output bearing fit, radial play or runout"},
      {"housing", "housing bore misalignment between the Circular Spline and the bearings"},
      {"wave_generator", "the wave generator: cam profile, flexible bearing or input bearing"},
      {"tooth_mesh", "tooth spacing or profile (base pitch)"},
  };
  for (const auto& [family, text] : kSuspects) {
    if (first.family == family) return text;
  }
  return first.source.empty() ? "not a line of the twin's model: unattributed"
                              : "the twin's term " + first.source;
}

std::vector<RankedSource> rank_sources_at_order(const model::GearParams& twin, double ratio,
                                                int order, int max_harmonic) {
  // The twin's ranking in the order domain: time is the wave-generator angle in turns (one
  // turn per "second"), so a term's frequency is its WG order and an output order k sits at
  // k/N; one output revolution's record resolves 1/N.
  analysis::AttributionInput in;
  in.terms = twin.te_terms;
  in.geometry = twin.geometry;
  in.geometry.ratio = ratio;
  in.mean_input_speed = kTwoPi;
  in.resolution_hz = 1.0 / ratio;
  in.sample_rate_hz = 1e9;  // resampled finely enough that nothing the model names folds
  in.window = analysis::Window::kRectangular;
  in.use_transfer = false;
  analysis::SpectralPeak peak;
  peak.frequency_hz = order / ratio;
  std::vector<RankedSource> out;
  const auto attributed = analysis::attribute_peaks({peak}, in);
  for (const auto& src : attributed.front().sources) {
    const auto term = std::find_if(twin.te_terms.begin(), twin.te_terms.end(),
                                   [&](const model::TeTerm& t) { return t.source == src.source; });
    // Within the bin tolerance, only terms of this very order (a neighbour order is another line).
    if (term == twin.te_terms.end() || std::abs(output_order(*term, ratio) - order) > 0.5) continue;
    out.push_back(
        {src.source, te_family_name(term->family), src.share, src.predicted_amplitude, 1});
  }
  if (!out.empty()) {
    double total = 0;
    for (const auto& s : out) total += s.predicted_amplitude_rad;
    for (auto& s : out) s.share = total > 0 ? s.predicted_amplitude_rad / total : 0;
    return out;
  }
  // No term at the order: the terms it is a harmonic of (a pulse train's upper lines).
  double total = 0;
  for (const auto& t : twin.te_terms) {
    const double o = output_order(t, ratio);
    if (!(o >= 1) || t.amplitude_rad == 0) continue;
    const double n = order / o;
    if (std::abs(n - std::round(n)) > 1e-6 || std::round(n) > max_harmonic) continue;
    out.push_back({t.source, te_family_name(t.family), 0, std::abs(t.amplitude_rad),
                   static_cast<int>(std::round(n))});
    total += std::abs(t.amplitude_rad);
  }
  for (auto& s : out) s.share = total > 0 ? s.predicted_amplitude_rad / total : 0;
  std::sort(out.begin(), out.end(), [](const RankedSource& a, const RankedSource& b) {
    return a.predicted_amplitude_rad > b.predicted_amplitude_rad;
  });
  return out;
}

std::vector<FlaggedLine> lines_above_band(const std::vector<double>& residual,
                                          const std::vector<double>& predicted, double floor_rad,
                                          const ResidualWatchOptions& options, int max_order,
                                          double* largest_ratio, int* largest_ratio_order) {
  const int top = std::min<int>(max_order, static_cast<int>(residual.size()) - 1);
  std::vector<double> watched;
  for (int k = 1; k <= top; ++k) watched.push_back(residual[static_cast<std::size_t>(k)]);
  const double noise = options.noise_factor * median(watched);
  std::vector<FlaggedLine> out;
  double best = 0;
  int best_order = 0;
  for (int k = 1; k <= top; ++k) {
    const auto i = static_cast<std::size_t>(k);
    const double p = i < predicted.size() ? predicted[i] : 0.0;
    const double band =
        std::max({options.floor_factor * floor_rad, noise, options.relative_band * p});
    const double ratio = band > 0 ? residual[i] / band : 0;
    if (ratio > best) {
      best = ratio;
      best_order = k;
    }
    if (residual[i] > band) out.push_back({k, residual[i], band, p});
  }
  if (largest_ratio) *largest_ratio = best;
  if (largest_ratio_order) *largest_ratio_order = best_order;
  return out;
}

std::vector<std::vector<FlaggedLine>> harmonic_series(std::vector<FlaggedLine> lines,
                                                      int max_harmonic) {
  std::sort(lines.begin(), lines.end(),
            [](const FlaggedLine& a, const FlaggedLine& b) { return a.order < b.order; });
  std::vector<std::vector<FlaggedLine>> series;
  for (const auto& line : lines) {
    auto joined = std::find_if(series.begin(), series.end(), [&](const auto& s) {
      const int f = s.front().order;
      return line.order % f == 0 && line.order / f <= max_harmonic;
    });
    if (joined == series.end()) {
      series.push_back({line});
    } else {
      joined->push_back(line);
    }
  }
  return series;
}

std::vector<int> model_orders(const model::GearParams& twin, double ratio) {
  std::vector<int> out;
  for (const auto& t : twin.te_terms) {
    const double o = output_order(t, ratio);
    if (t.amplitude_rad != 0 && o >= 1 && std::abs(o - std::round(o)) < 1e-6) {
      out.push_back(static_cast<int>(std::round(o)));
    }
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

std::vector<std::vector<FlaggedLine>> attach_sidebands(std::vector<std::vector<FlaggedLine>> series,
                                                       const std::vector<double>& residual,
                                                       const std::vector<int>& known_orders,
                                                       const ResidualWatchOptions& options) {
  // Exact orders only: the low harmonics of the 1/rev would cover every order below 9, where
  // a defect's appearing mean (its pulse's average) spreads too.
  const auto known = [&](int order) {
    return std::binary_search(known_orders.begin(), known_orders.end(), order);
  };
  const auto series_of = [&](int order) {
    return std::find_if(series.begin(), series.end(), [&](const auto& s) {
      return std::any_of(s.begin(), s.end(),
                         [&](const FlaggedLine& l) { return l.order == order; });
    });
  };
  std::vector<bool> gone(series.size(), false);
  for (std::size_t i = 0; i < series.size(); ++i) {
    const int f = series[i].front().order;
    if (known(f)) continue;
    double largest = 0;
    for (const auto& l : series[i]) largest = std::max(largest, l.amplitude_rad);
    // The strongest other line near it, flagged or not.
    int host = 0;
    double host_amplitude = 0;
    const auto own = series.begin() + static_cast<std::ptrdiff_t>(i);
    for (int k = std::max(1, f - options.max_sideband);
         k <= f + options.max_sideband && k < static_cast<int>(residual.size()); ++k) {
      if (series_of(k) == own) continue;
      const double a = residual[static_cast<std::size_t>(k)];
      if (a > host_amplitude) {
        host_amplitude = a;
        host = k;
      }
    }
    if (host == 0 || host_amplitude < options.sideband_ratio * largest) continue;
    gone[i] = true;
    const auto into = series_of(host);
    if (into != series.end() && !gone[static_cast<std::size_t>(into - series.begin())]) {
      into->insert(into->end(), series[i].begin(), series[i].end());
    }
  }
  std::vector<std::vector<FlaggedLine>> kept;
  for (std::size_t i = 0; i < series.size(); ++i) {
    if (gone[i]) continue;
    std::sort(series[i].begin() + 1, series[i].end(),
              [](const FlaggedLine& a, const FlaggedLine& b) { return a.order < b.order; });
    kept.push_back(std::move(series[i]));
  }
  return kept;
}

ResidualWatch::ResidualWatch(const model::GearParams& twin, double ratio,
                             ResidualWatchOptions options)
    : twin_(twin),
      ratio_(ratio),
      options_(options),
      analyser_(std::make_unique<analysis::SpectrumAnalyser>()),
      known_orders_(model_orders(twin, ratio)) {
  report_.options = options_;
}

ResidualWatch::~ResidualWatch() = default;

void ResidualWatch::restart(const TwinPoint& point) {
  window_.clear();
  window_.push_back(point);
  start_theta_ = point.theta1_rad;
  direction_ = 0;
}

void ResidualWatch::feed(const TwinPoint& point) {
  if (!std::isfinite(point.measured_te_rad) || !std::isfinite(point.predicted_te_rad) ||
      !std::isfinite(point.theta1_rad)) {
    return;
  }
  if (window_.empty()) {
    restart(point);
    return;
  }
  const double step = point.theta1_rad - window_.back().theta1_rad;
  if (direction_ == 0) {
    // Not yet moving: the window starts where the input leaves its place.
    if (std::abs(point.theta1_rad - start_theta_) < options_.reversal_rad) {
      window_.back() = point;
      start_theta_ = point.theta1_rad;
      return;
    }
    direction_ = point.theta1_rad > start_theta_ ? 1 : -1;
  }
  if (!(direction_ * step > 0)) {
    // Standing still or jitter: nothing new in angle. A real reversal starts over.
    if (direction_ * (point.theta1_rad - window_.back().theta1_rad) < -options_.reversal_rad) {
      restart(point);
    }
    return;
  }
  window_.push_back(point);
  if (direction_ * (point.theta1_rad - start_theta_) >= kTwoPi * ratio_) {
    analyse_revolution();
    const TwinPoint last = window_.back();
    const int direction = direction_;
    restart(last);
    direction_ = direction;
  }
}

void ResidualWatch::analyse_revolution() {
  ++revolution_;
  if (window_.size() < std::max<std::size_t>(options_.min_samples_per_revolution, 4) ||
      !steady(window_, start_theta_, kTwoPi * ratio_)) {
    ++report_.unsteady_revolutions;
    return;
  }
  // Exactly one revolution: the last sample moved onto start ± 2πN by interpolation.
  const double end = start_theta_ + direction_ * kTwoPi * ratio_;
  std::vector<double> theta, residual, predicted;
  theta.reserve(window_.size());
  for (const auto& p : window_) {
    theta.push_back(p.theta1_rad);
    residual.push_back(p.measured_te_rad - p.predicted_te_rad);
    predicted.push_back(p.predicted_te_rad);
  }
  // The sample before may already sit on the end (within a rounding of the test in feed()).
  while (theta.size() > 2 && direction_ * (theta[theta.size() - 2] - end) >= 0) {
    theta.pop_back();
    residual.pop_back();
    predicted.pop_back();
  }
  const std::size_t n = theta.size();
  const double u = (end - theta[n - 2]) / (theta[n - 1] - theta[n - 2]);
  theta[n - 1] = end;
  residual[n - 1] = residual[n - 2] + u * (residual[n - 1] - residual[n - 2]);
  predicted[n - 1] = predicted[n - 2] + u * (predicted[n - 1] - predicted[n - 2]);

  // A multiple of 64 points, so that revolutions of slightly different sample counts share an
  // FFT plan.
  const std::size_t points = std::max<std::size_t>(64, (n - 1) / 64 * 64);
  double step = 0;
  auto r = analysis::resample_on_angle(theta, residual, points + 1, &step);
  auto p = analysis::resample_on_angle(theta, predicted, points + 1, &step);
  r.pop_back();
  p.pop_back();
  const double per_rev = static_cast<double>(points);
  const auto rs = analyser_->analyse(r, per_rev, analysis::Window::kRectangular);
  const auto ps = analyser_->analyse(p, per_rev, analysis::Window::kRectangular);

  RevolutionSummary summary;
  summary.revolution = revolution_;
  summary.t_start_s = window_.front().t_s;
  summary.t_end_s = window_.back().t_s;
  summary.samples = n;
  double mean = 0;
  for (double v : r) mean += v;
  mean /= per_rev;
  double squares = 0;
  for (double v : r) squares += (v - mean) * (v - mean);
  summary.residual_rms_rad = std::sqrt(squares / per_rev);
  // The configured noise: the residual's own third differences also hold a tooth pulse's
  // edges (a few samples wide at speed), so they measure the floor only without a defect.
  summary.floor_rad = options_.sensor_noise_rad > 0
                          ? options_.sensor_noise_rad
                          : estimate_te_noise_floor_arcsec(window_) * model::kRadPerArcsec;
  const int nyquist = static_cast<int>(rs.amplitude.size()) - 1;
  const int max_order = options_.max_order > 0 ? std::min(options_.max_order, nyquist) : nyquist;
  const auto lines =
      lines_above_band(rs.amplitude, ps.amplitude, summary.floor_rad, options_, max_order,
                       &summary.largest_ratio, &summary.largest_ratio_order);
  report_.revolutions.push_back(summary);

  for (auto& series : attach_sidebands(harmonic_series(lines, options_.max_harmonic), rs.amplitude,
                                       known_orders_, options_)) {
    const FlaggedLine& fundamental = series.front();
    auto known =
        std::find_if(report_.flags.begin(), report_.flags.end(),
                     [&](const DiagnosticFlag& f) { return f.order == fundamental.order; });
    if (known != report_.flags.end()) {
      known->last_revolution = revolution_;
      ++known->revolutions;
      known->amplitude_rad = std::max(known->amplitude_rad, fundamental.amplitude_rad);
      continue;
    }
    DiagnosticFlag flag;
    flag.order = fundamental.order;
    flag.amplitude_rad = fundamental.amplitude_rad;
    flag.band_rad = fundamental.band_rad;
    flag.first_revolution = flag.last_revolution = revolution_;
    flag.revolutions = 1;
    flag.onset_t_s = summary.t_start_s;
    flag.first_t_s = summary.t_end_s;
    flag.lines = series;
    flag.sources = rank_sources_at_order(twin_, ratio_, flag.order, options_.max_harmonic);
    flag.suspect = flag.sources.empty() ? suspect_for({}) : suspect_for(flag.sources.front());
    report_.flags.push_back(flag);
    if (on_flag_) on_flag_(report_.flags.back());
  }
}

std::string describe(const DiagnosticFlag& f) {
  std::ostringstream s;
  s.precision(3);
  s << "order " << f.order << " of the output revolution: residual " << arcsec(f.amplitude_rad)
    << " arcsec, " << (f.band_rad > 0 ? f.amplitude_rad / f.band_rad : 0.0)
    << "x its band, from revolution " << f.first_revolution << " (t = " << f.first_t_s
    << " s); the twin ranks there: ";
  if (f.sources.empty()) s << "nothing";
  for (std::size_t i = 0; i < f.sources.size() && i < 3; ++i) {
    if (i) s << ", ";
    s << f.sources[i].source;
    if (f.sources[i].harmonic > 1) s << " (harmonic " << f.sources[i].harmonic << ")";
  }
  s << " — " << f.suspect;
  return s.str();
}

nlohmann::json to_json(const DiagnosticFlag& f) {
  nlohmann::json lines = nlohmann::json::array();
  for (const auto& l : f.lines) {
    lines.push_back({{"order", l.order},
                     {"amplitude_arcsec", arcsec(l.amplitude_rad)},
                     {"band_arcsec", arcsec(l.band_rad)},
                     {"predicted_arcsec", arcsec(l.predicted_rad)}});
  }
  nlohmann::json sources = nlohmann::json::array();
  for (const auto& s : f.sources) {
    sources.push_back({{"source", s.source},
                       {"family", s.family},
                       {"share", s.share},
                       {"predicted_arcsec", arcsec(s.predicted_amplitude_rad)},
                       {"harmonic", s.harmonic}});
  }
  return {{"order", f.order},
          {"amplitude_arcsec", arcsec(f.amplitude_rad)},
          {"band_arcsec", arcsec(f.band_rad)},
          {"first_revolution", f.first_revolution},
          {"onset_s", f.onset_t_s},
          {"flagged_s", f.first_t_s},
          {"last_revolution", f.last_revolution},
          {"revolutions", f.revolutions},
          {"lines", lines},
          {"sources", sources},
          {"suspect", f.suspect},
          {"text", describe(f)}};
}

nlohmann::json to_json(const DiagnosticReport& r) {
  nlohmann::json revolutions = nlohmann::json::array();
  for (const auto& v : r.revolutions) {
    revolutions.push_back({{"revolution", v.revolution},
                           {"t_start_s", v.t_start_s},
                           {"t_end_s", v.t_end_s},
                           {"samples", v.samples},
                           {"residual_rms_arcsec", arcsec(v.residual_rms_rad)},
                           {"floor_arcsec", arcsec(v.floor_rad)},
                           {"largest_ratio", v.largest_ratio},
                           {"largest_ratio_order", v.largest_ratio_order}});
  }
  nlohmann::json flags = nlohmann::json::array();
  for (const auto& f : r.flags) flags.push_back(to_json(f));
  return {{"band",
           {{"relative_band", r.options.relative_band},
            {"floor_factor", r.options.floor_factor},
            {"noise_factor", r.options.noise_factor},
            {"sensor_noise_arcsec", arcsec(r.options.sensor_noise_rad)},
            {"max_harmonic", r.options.max_harmonic}}},
          {"revolutions", revolutions},
          {"unsteady_revolutions", r.unsteady_revolutions},
          {"flags", flags}};
}

}  // namespace wavebench::twin
