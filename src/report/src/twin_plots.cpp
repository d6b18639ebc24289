#include "wavebench/report/twin_plots.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "wavebench/model/angle_units.hpp"

namespace wavebench::report {
namespace {

std::vector<double> scaled(const std::vector<double>& v, double k) {
  std::vector<double> out(v.size());
  std::transform(v.begin(), v.end(), out.begin(), [k](double x) { return x * k; });
  return out;
}

// The samples of [t0, t1) of a channel.
void window(const std::vector<double>& t, const std::vector<double>& y, double t0, double t1,
            std::vector<double>& tw, std::vector<double>& yw) {
  const std::size_t n = std::min(t.size(), y.size());
  for (std::size_t i = 0; i < n; ++i) {
    if (t[i] >= t0 && t[i] < t1) {
      tw.push_back(t[i]);
      yw.push_back(y[i]);
    }
  }
}

std::string peak_text(const NamedPeak& p) {
  char buf[48];
  std::snprintf(buf, sizeof buf, p.frequency_hz < 1000 ? "%.2f Hz" : "%.0f Hz", p.frequency_hz);
  return p.label.empty() ? std::string(buf) : std::string(buf) + " " + p.label;
}

}  // namespace

Figure time_response_figure(const model::SampledResponse& r, const std::string& title,
                            double zoom_seconds) {
  Figure fig(2, 2, title);
  const auto te = scaled(r.te, model::kArcsecPerRad);
  fig.axes(0, 0).line(r.t, te).title = "Transmission error (whole record)";
  fig.axes(0, 0).x_label = "t [s]";
  fig.axes(0, 0).y_label = "TE [arcsec]";
  fig.axes(1, 0).line(r.t, r.alpha2, {}, palette(1)).title = "Output acceleration";
  fig.axes(1, 0).x_label = "t [s]";
  fig.axes(1, 0).y_label = "alpha2 [rad/s^2]";
  if (!r.t.empty()) {
    const double t0 = r.t.front();
    const double t1 = t0 + std::max(zoom_seconds, 1e-9);
    std::vector<double> tw, yw, ta, ya;
    window(r.t, te, t0, t1, tw, yw);
    window(r.t, r.alpha2, t0, t1, ta, ya);
    char buf[64];
    std::snprintf(buf, sizeof buf, "first %.3g s of the record", t1 - t0);
    fig.axes(0, 1).line(tw, yw).title = std::string("TE, ") + buf;
    fig.axes(1, 1).line(ta, ya, {}, palette(1)).title = std::string("Output acceleration, ") + buf;
  }
  fig.axes(0, 1).x_label = fig.axes(1, 1).x_label = "t [s]";
  fig.axes(0, 1).y_label = "TE [arcsec]";
  fig.axes(1, 1).y_label = "alpha2 [rad/s^2]";
  return fig;
}

Figure spectrum_figure(const std::vector<double>& f, const std::vector<double>& amplitude,
                       const std::vector<NamedPeak>& peaks, const std::string& amplitude_label,
                       const std::string& title) {
  Figure fig(2, 1, title);
  Axes& full = fig.axes(0, 0);
  full.title = "Amplitude spectrum";
  full.x_label = "frequency [Hz]";
  full.y_label = amplitude_label;
  full.log_y = true;
  // Skip DC for a log frequency axis; span decades when the lines do.
  std::vector<double> fx, ay;
  for (std::size_t i = 0; i < std::min(f.size(), amplitude.size()); ++i) {
    if (f[i] > 0) {
      fx.push_back(f[i]);
      ay.push_back(amplitude[i]);
    }
  }
  const bool wide = !fx.empty() && fx.back() / fx.front() > 100;
  full.log_x = wide;
  if (wide) full.x_min = std::max(fx.front(), 1.0);
  full.line(fx, ay);
  for (const auto& p : peaks) full.annotate(p.frequency_hz, p.amplitude, peak_text(p));

  Axes& zoom = fig.axes(1, 0);
  zoom.x_label = "frequency [Hz]";
  zoom.y_label = amplitude_label;
  const auto largest = std::max_element(
      peaks.begin(), peaks.end(),
      [](const NamedPeak& a, const NamedPeak& b) { return a.amplitude < b.amplitude; });
  if (largest != peaks.end()) {
    const double fc = largest->frequency_hz;
    const double half = std::max(2.0, 0.08 * fc);
    std::vector<double> zf, za;
    for (std::size_t i = 0; i < fx.size(); ++i) {
      if (fx[i] >= fc - half && fx[i] <= fc + half) {
        zf.push_back(fx[i]);
        za.push_back(ay[i]);
      }
    }
    zoom.line(zf, za);
    zoom.x_min = fc - half;
    zoom.x_max = fc + half;
    zoom.y_min = 0;
    for (const auto& p : peaks) {
      if (std::abs(p.frequency_hz - fc) <= half)
        zoom.annotate(p.frequency_hz, p.amplitude, peak_text(p));
    }
    char buf[80];
    std::snprintf(buf, sizeof buf, "Around the largest line (%.2f Hz), linear", fc);
    zoom.title = buf;
  } else {
    zoom.title = "No peaks found";
  }
  return fig;
}

Figure phase_portrait_figure(const std::vector<PortraitPanel>& panels, const std::string& title) {
  Figure fig(1, std::max<int>(1, static_cast<int>(panels.size())), title);
  for (std::size_t i = 0; i < panels.size(); ++i) {
    Axes& ax = fig.axes(0, static_cast<int>(i));
    ax.title = panels[i].title;
    ax.x_label = panels[i].x_label;
    ax.y_label = panels[i].v_label;
    ax.line(panels[i].x, panels[i].v, {}, palette(static_cast<int>(i)));
    ax.series.back().width = 0.6;
  }
  return fig;
}

Figure poincare_figure(const std::vector<double>& x, const std::vector<double>& v,
                       const std::string& x_label, const std::string& v_label,
                       const std::string& motion_class, const std::string& title) {
  Figure fig(1, 1, title);
  Axes& ax = fig.axes(0, 0);
  ax.title = "Poincare section: " + motion_class + " (" + std::to_string(x.size()) + " points)";
  ax.x_label = x_label;
  ax.y_label = v_label;
  ax.scatter(x, v, {}, palette(3), x.size() > 3000 ? 1.5 : 2.5);
  return fig;
}

Figure bifurcation_figure(const std::vector<SweepBranch>& branches, const std::string& value_label,
                          const std::string& amplitude_label,
                          const std::vector<double>& jump_speeds_rpm, const std::string& title) {
  Figure fig(2, 1, title);
  Axes& bif = fig.axes(0, 0);
  bif.title = "Bifurcation diagram (Poincare values against speed)";
  bif.x_label = "input speed [rpm]";
  bif.y_label = value_label;
  Axes& amp = fig.axes(1, 0);
  amp.title = "Response amplitude, sweep up and down";
  amp.x_label = "input speed [rpm]";
  amp.y_label = amplitude_label;
  int colour = 0;
  for (const auto& b : branches) {
    std::vector<double> sx, sy;
    for (std::size_t i = 0; i < std::min(b.speed_rpm.size(), b.section_values.size()); ++i) {
      for (const double v : b.section_values[i]) {
        sx.push_back(b.speed_rpm[i]);
        sy.push_back(v);
      }
    }
    bif.scatter(sx, sy, b.label, palette(colour), 1.6);
    amp.line(b.speed_rpm, b.amplitude, b.label, palette(colour));
    amp.scatter(b.speed_rpm, b.amplitude, {}, palette(colour), 2.5);
    ++colour;
  }
  for (const double s : jump_speeds_rpm) {
    double a = 0;
    for (const auto& b : branches) {
      for (std::size_t i = 0; i < std::min(b.speed_rpm.size(), b.amplitude.size()); ++i) {
        if (b.speed_rpm[i] == s) a = std::max(a, b.amplitude[i]);
      }
    }
    char buf[48];
    std::snprintf(buf, sizeof buf, "jump %.0f rpm", s);
    amp.annotate(s, a, buf);
  }
  return fig;
}

}  // namespace wavebench::report
