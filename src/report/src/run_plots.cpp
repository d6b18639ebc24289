#include "wavebench/report/run_plots.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <numbers>

#include "wavebench/metrology/dynamic_te_analysis.hpp"
#include "wavebench/metrology/lost_motion_fit.hpp"
#include "wavebench/model/angle_units.hpp"
#include "wavebench/report/dynamic_plot_data.hpp"

namespace wavebench::report {
namespace {

using nlohmann::json;
// Cairo draws a few tens of thousands of points quickly; more only blurs into the same ink.
constexpr std::size_t kMaxPlotPoints = 20000;

void thin(std::vector<double>& x, std::vector<double>& y) {
  const std::size_t n = std::min(x.size(), y.size());
  if (n <= kMaxPlotPoints) return;
  const std::size_t stride = (n + kMaxPlotPoints - 1) / kMaxPlotPoints;
  std::size_t k = 0;
  for (std::size_t i = 0; i < n; i += stride, ++k) {
    x[k] = x[i];
    y[k] = y[i];
  }
  x.resize(k);
  y.resize(k);
}

double median(std::vector<double> v) {
  if (v.empty()) return std::nan("");
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

std::string text_of(const json& j, const std::string& key) {
  const auto it = j.find(key);
  return it != j.end() && it->is_string() ? it->get<std::string>() : std::string();
}

std::string load_label(double load_nm) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "%g N*m", load_nm);
  return buf;
}

}  // namespace

std::optional<DynamicTrace> dynamic_trace(const std::vector<storage::SyncSample>& samples,
                                          const metrology::GearSense& sense) {
  std::vector<double> t, th_in, th_out;
  for (const auto& s : samples) {
    if (!s.valid(storage::kThetaInValid) || !s.valid(storage::kThetaOutValid)) continue;
    const double ts = 1e-9 * static_cast<double>(s.receive_time_ns);
    if (!t.empty() && ts <= t.back()) continue;  // out of order: no spectrum can use it
    t.push_back(ts);
    th_in.push_back(s.theta_in_rad);
    th_out.push_back(s.theta_out_rad);
  }
  if (t.size() < 16 || !(sense.ratio > 0)) return std::nullopt;
  // Input speed over windows long enough that a late SYNC's timestamp does not dominate.
  const std::size_t w = std::clamp<std::size_t>(t.size() / 50, 1, 200);
  std::vector<double> speed(t.size() - w);
  for (std::size_t i = 0; i + w < t.size(); ++i) {
    speed[i] = (th_in[i + w] - th_in[i]) / (t[i + w] - t[i]);
  }
  const double steady = median(speed);
  if (!(std::abs(steady) > 1e-6)) return std::nullopt;
  const auto is_steady = [&](double v) { return std::abs(v - steady) <= 0.02 * std::abs(steady); };
  // Windows are averages: the trace starts where a steady window ends and stops where the
  // last steady window starts, so no sample of the run-in or the stop gets in.
  std::size_t first = 0;
  while (first < speed.size() && !is_steady(speed[first])) ++first;
  std::size_t last = speed.size();
  while (last > first && !is_steady(speed[last - 1])) --last;
  first += w;
  if (last < first + 16) return std::nullopt;
  DynamicTrace trace;
  for (std::size_t i = first; i < last; ++i) {
    trace.time_s.push_back(t[i] - t[first]);
    trace.output_angle_deg.push_back(
        (sense.model_output_angle(th_out[i]) - sense.model_output_angle(th_out[first])) *
        model::kDegPerRad);
    trace.te_arcsec.push_back(sense.transmission_error(th_in[i], th_out[i]) *
                              metrology::kArcsecPerRad);
  }
  const double span = t[last - 1] - t[first];
  trace.input_speed_hz =
      span > 0 ? std::abs(th_in[last - 1] - th_in[first]) / span / (2 * std::numbers::pi) : 0;
  return trace;
}

std::optional<DynamicTrace> dynamic_trace(const json& dynamic) {
  const auto it = dynamic.find("trace");
  if (it == dynamic.end() || !it->is_object()) return std::nullopt;
  DynamicTrace trace;
  const auto column = [&](const char* key, std::vector<double>& out) {
    const auto c = it->find(key);
    if (c == it->end() || !c->is_array()) return;
    for (const auto& v : *c) out.push_back(v.is_number() ? v.get<double>() : std::nan(""));
  };
  column("time_s", trace.time_s);
  column("output_angle_deg", trace.output_angle_deg);
  column("te_arcsec", trace.te_arcsec);
  const std::size_t n = trace.te_arcsec.size();
  if (n < 16 || trace.time_s.size() != n || trace.output_angle_deg.size() != n) return std::nullopt;
  for (std::size_t i = 1; i < n; ++i) {
    if (!(trace.time_s[i] > trace.time_s[i - 1])) return std::nullopt;  // no spectrum from it
  }
  trace.input_speed_hz = number(dynamic, "input_speed_hz").value_or(0);
  return trace;
}

std::optional<Figure> static_te_figure(const json& passes) {
  if (!passes.is_array()) return std::nullopt;
  std::map<double, std::vector<const json*>> by_load;
  for (const auto& p : passes) {
    const auto load = number(p, "load_nm");
    const auto pts = p.find("points");
    if (!load || pts == p.end() || !pts->is_array() || pts->empty()) continue;
    by_load[*load].push_back(&p);
  }
  if (by_load.empty()) return std::nullopt;
  Figure fig(static_cast<int>(by_load.size()), 1, "Static TE against output angle");
  std::optional<double> reference;  // output angle of the first point, every pass
  int row = 0;
  for (const auto& [load, group] : by_load) {
    Axes& ax = fig.axes(row++, 0);
    ax.title = "Load " + load_label(load);
    ax.x_label = "output angle from position 0 [deg]";
    ax.y_label = "TE [arcmin]";
    for (const json* pass : group) {
      const double half_step = 180.0 / static_cast<double>((*pass)["points"].size());
      std::vector<std::pair<double, double>> pts;
      for (const auto& pt : (*pass)["points"]) {
        const auto a = number(pt, "output_angle_deg");
        const auto te = number(pt, "te_arcmin");
        if (!a || !te) continue;
        // TE repeats with the output revolution and the angle may be multi-turn (unwrapped):
        // angles from position 0, within one revolution, a half step either side of it kept
        // together (position 0 reached from either side).
        if (!reference) reference = *a;
        double d = std::fmod(*a - *reference, 360.0);
        if (d < -half_step) d += 360;
        if (d >= 360 - half_step) d -= 360;
        pts.emplace_back(d, *te);
      }
      std::sort(pts.begin(), pts.end());
      std::vector<double> x, y;
      for (const auto& [a, te] : pts) {
        x.push_back(a);
        y.push_back(te);
      }
      const std::string dir = text_of(*pass, "direction");
      const Color c = palette(dir == "reverse" ? 1 : 0);
      ax.line(x, y, {}, c);
      ax.scatter(x, y, dir.empty() ? "pass" : dir, c, 3.0);
    }
  }
  return fig;
}

std::optional<Figure> dynamic_te_figure(const DynamicPlotData& data) {
  if (data.te_by_time.t.empty() || data.te_by_time.series.empty()) return std::nullopt;
  Figure fig(2, 1, "Dynamic TE");
  const auto drawn = [](const analysis::DecimatedTrace& d) {
    return d.full_resolution ? std::string()
                             : " - min/max per pixel column of " +
                                   std::to_string(d.samples_in_range) + " samples";
  };
  Axes& angle = fig.axes(0, 0);
  angle.line(data.te_by_angle.t, data.te_by_angle.series.at(0));
  angle.title = "TE against output angle (steady speed)" + drawn(data.te_by_angle);
  angle.x_label = "output angle [deg]";
  angle.y_label = "TE [arcsec]";
  Axes& time = fig.axes(1, 0);
  time.line(data.te_by_time.t, data.te_by_time.series.at(0), {}, palette(2));
  time.title = "TE against time" + drawn(data.te_by_time);
  time.x_label = "t [s]";
  time.y_label = "TE [arcsec]";
  return fig;
}

std::optional<Figure> dynamic_spectrum_figure(const DynamicPlotData* data, const json& dynamic,
                                              double ratio) {
  const auto peaks_it = dynamic.find("peaks");
  const bool have_peaks = peaks_it != dynamic.end() && peaks_it->is_array() &&
                          std::any_of(peaks_it->begin(), peaks_it->end(), [](const json& p) {
                            return number(p, "frequency_hz") && number(p, "amplitude_arcsec");
                          });
  const analysis::AmplitudeSpectrum* spectrum = data && data->spectrum ? &*data->spectrum : nullptr;
  if (!spectrum && !have_peaks) return std::nullopt;
  double f_in = number(dynamic, "input_speed_hz").value_or(data ? data->input_speed_hz : 0.0);
  const double f_out = ratio > 0 ? f_in / ratio : 0;

  Figure fig(f_out > 0 ? 2 : 1, 1, "Dynamic TE spectrum");
  Axes& hz = fig.axes(0, 0);
  hz.title = "Amplitude spectrum with named peaks";
  if (spectrum && data->spectrum_segments > 0) {
    char buf[120];
    std::snprintf(buf, sizeof buf,
                  " (averaged over %zu Hann segments of %zu samples, half overlapping)",
                  data->spectrum_segments, spectrum->samples);
    hz.title += buf;
  }
  hz.x_label = "frequency [Hz]";
  hz.y_label = "TE amplitude [arcsec]";
  hz.log_y = true;
  // The lines of a TE spectrum sit from 1/rev of the output (a fraction of a hertz) up to
  // Nyquist: only a log frequency axis shows them all.
  hz.log_x = true;
  std::vector<double> f, a;
  if (spectrum) {
    for (std::size_t i = 1; i < spectrum->frequency_hz.size();
         ++i) {  // DC says nothing on a log axis
      f.push_back(spectrum->frequency_hz[i]);
      a.push_back(spectrum->amplitude[i]);
    }
    hz.line(f, a);
  }
  double f_max = f.empty() ? 0 : f.back();
  if (have_peaks) {
    std::vector<double> px, py;
    for (const auto& p : *peaks_it) {
      const auto fp = number(p, "frequency_hz");
      const auto ap = number(p, "amplitude_arcsec");
      if (!fp || !ap || *ap <= 0) continue;
      px.push_back(*fp);
      py.push_back(*ap);
      f_max = std::max(f_max, *fp);
      std::string label = text_of(p, "name");
      if (const auto o = number(p, "order_output")) {
        char buf[40];
        std::snprintf(buf, sizeof buf, " (%.3g/rev)", *o);
        label += buf;
      }
      hz.annotate(*fp, *ap, label);
    }
    if (f.empty()) hz.scatter(px, py, "named peaks", palette(1), 3.0);
  }
  if (const auto al = dynamic.find("aliased"); al != dynamic.end() && al->is_array()) {
    for (const auto& c : *al) {
      const auto folded = number(c, "folded_hz");
      const auto amp = number(c, "amplitude_arcsec");
      if (!folded || !amp || *amp <= 0 || (f_max > 0 && *folded > f_max)) continue;
      hz.annotate(*folded, *amp, "aliased: " + text_of(c, "name"), false);
    }
  }
  if (f_out > 0) {
    Axes& ord = fig.axes(1, 0);
    ord.title = "Against output orders (cycles per output revolution)";
    ord.x_label = "output order";
    ord.y_label = "TE amplitude [arcsec]";
    ord.log_y = true;
    ord.log_x = true;
    std::vector<double> o(f.size());
    std::transform(f.begin(), f.end(), o.begin(), [f_out](double v) { return v / f_out; });
    if (!o.empty()) ord.line(o, a);
    if (have_peaks) {
      std::vector<double> px, py;
      for (const auto& p : *peaks_it) {
        const auto op = number(p, "order_output");
        const auto ap = number(p, "amplitude_arcsec");
        if (!op || !ap || *ap <= 0) continue;
        ord.annotate(*op, *ap, text_of(p, "name"));
        px.push_back(*op);
        py.push_back(*ap);
      }
      if (o.empty()) ord.scatter(px, py, "named peaks", palette(1), 3.0);
    }
  }
  return fig;
}

std::optional<TorqueTwistCurve> torque_twist_from_results(const json& fit) {
  const json* pts = nullptr;
  for (const char* key : {"points", "record"}) {
    const auto it = fit.find(key);
    if (it != fit.end() && it->is_array()) pts = &*it;
  }
  if (!pts) return std::nullopt;
  TorqueTwistCurve c;
  for (const auto& p : *pts) {
    const auto torque = number(p, "torque_nm");
    std::optional<double> twist;
    if (const auto r = number(p, "twist_rad")) twist = *r * metrology::kArcminPerRad;
    if (const auto a = number(p, "twist_arcmin")) twist = *a;
    if (const auto s = number(p, "twist_arcsec")) twist = *s / 60;
    if (!torque || !twist) continue;
    const auto travel = number(p, "travel");
    c.twist_arcmin.push_back(*twist);
    c.torque_nm.push_back(*torque);
    c.travel.push_back(travel ? (*travel < 0 ? -1 : 1) : (*torque < 0 ? -1 : 1));
  }
  if (c.torque_nm.size() < 2) return std::nullopt;
  c.twist_label = "twist [arcmin]";
  return c;
}

std::optional<TorqueTwistCurve> torque_twist_from_samples(
    const std::vector<storage::SyncSample>& samples, const metrology::GearSense& sense) {
  TorqueTwistCurve c;
  for (const auto& s : samples) {
    if (!s.valid(storage::kThetaInValid) || !s.valid(storage::kThetaOutValid) ||
        !s.valid(storage::kTorqueValid)) {
      continue;
    }
    // Twist θ1/N − θ2 = −TE, as the fits' points give it.
    c.twist_arcmin.push_back(-sense.transmission_error(s.theta_in_rad, s.theta_out_rad) *
                             metrology::kArcminPerRad);
    c.torque_nm.push_back(s.torque_nm);
    // A brake only resists motion, so the torque's sign is the direction of travel.
    c.travel.push_back(s.torque_nm < 0 ? -1 : 1);
  }
  if (c.torque_nm.size() < 8) return std::nullopt;
  c.twist_label = "twist (-TE at the output, every sample) [arcmin]";
  c.from_samples = true;
  return c;
}

std::optional<Figure> hysteresis_figure(const TorqueTwistCurve& curve, const json* fit) {
  const std::size_t n = std::min(curve.twist_arcmin.size(), curve.torque_nm.size());
  if (n < 2) return std::nullopt;
  Figure fig(1, 1, "Lost motion and hysteresis");
  Axes& ax = fig.axes(0, 0);
  ax.title = "Torque against twist";
  ax.x_label = curve.twist_label;
  ax.y_label = "torque [N*m]";
  double t_max = 0;
  for (std::size_t i = 0; i < n; ++i) t_max = std::max(t_max, std::abs(curve.torque_nm[i]));
  auto x = curve.twist_arcmin, y = curve.torque_nm;
  x.resize(n);
  y.resize(n);
  if (curve.from_samples) {
    thin(x, y);
    ax.scatter(x, y, "measured", palette(0), 1.8);
  } else {
    ax.scatter(x, y, "measured", palette(0), 3.0);
  }
  if (!fit || t_max <= 0) return fig;
  // The fitted model per travel branch as results.json carries it (lost_motion_fit.fit_curve,
  // computed once by the procedure): drawn, not recomputed.
  std::optional<double> forward_offset, any_offset;
  const auto curves = fit->find("fit_curve");
  if (curves != fit->end() && curves->is_array()) {
    for (const auto& b : *curves) {
      if (!b.is_object()) continue;
      const auto& ts = b.value("torque_nm", json::array());
      const auto& xs = b.value("twist_arcmin", json::array());
      std::vector<double> bx, by;
      for (std::size_t i = 0; i < std::min(ts.size(), xs.size()); ++i) {
        if (!ts[i].is_number() || !xs[i].is_number()) continue;
        bx.push_back(xs[i].get<double>());
        by.push_back(ts[i].get<double>());
      }
      if (bx.empty()) continue;
      const bool reverse = number(b, "travel").value_or(1) < 0;
      ax.line(bx, by, reverse ? "fit, reverse travel" : "fit, forward travel",
              palette(reverse ? 3 : 1))
          .series.back()
          .width = 2.2;
      const auto o = number(b, "offset_arcmin");
      if (!reverse && o) forward_offset = o;
      if (o && !any_offset) any_offset = o;
    }
  }
  const auto& st = fit->value("stiffness", json::object());
  char buf[160];
  if (const auto k1 = number(st, "k1_nm_per_rad")) {
    std::snprintf(buf, sizeof buf, " - K1 %.3g, K2 %.3g, K3 %.3g N*m/rad; T1 %.3g, T2 %.3g N*m",
                  *k1, number(st, "k2_nm_per_rad").value_or(0),
                  number(st, "k3_nm_per_rad").value_or(0), number(st, "t1_nm").value_or(0),
                  number(st, "t2_nm").value_or(0));
    ax.title += buf;
  }
  if (const auto lm = number(*fit, "lost_motion_arcmin"); lm && any_offset) {
    const auto at = number(*fit, "lost_motion_torque_nm");
    std::snprintf(buf, sizeof buf, "lost motion %.2f arcmin at +/-%.3g N*m", *lm, at.value_or(0));
    ax.annotate(forward_offset.value_or(*any_offset), 0, buf, false);
  }
  return fig;
}

std::optional<Figure> twin_figure(const TwinTrace& twin) {
  const std::size_t n = twin.t.size();
  if (n < 2) return std::nullopt;
  Figure fig(2, 1, "The twin beside the bench");
  Axes& te = fig.axes(0, 0);
  te.title = "Measured and predicted TE";
  te.x_label = "t [s]";
  te.y_label = "TE [arcsec]";
  if (twin.measured_te_arcsec.size() == n) {
    auto t = twin.t, y = twin.measured_te_arcsec;
    thin(t, y);
    te.line(t, y, "measured", palette(0));
  }
  if (twin.predicted_te_arcsec.size() == n) {
    auto t = twin.t, y = twin.predicted_te_arcsec;
    thin(t, y);
    te.line(t, y, "twin", palette(1));
  }
  std::vector<double> residual = twin.residual_arcsec;
  if (residual.size() != n && twin.measured_te_arcsec.size() == n &&
      twin.predicted_te_arcsec.size() == n) {
    residual.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      residual[i] = twin.measured_te_arcsec[i] - twin.predicted_te_arcsec[i];
    }
  }
  Axes& res = fig.axes(1, 0);
  res.title = "Residual (measured - twin)";
  res.x_label = "t [s]";
  res.y_label = "residual [arcsec]";
  if (residual.size() == n) {
    auto t = twin.t;
    thin(t, residual);
    res.line(t, residual, {}, palette(2));
  }
  if (te.series.empty() && res.series.empty()) return std::nullopt;
  return fig;
}

}  // namespace wavebench::report
