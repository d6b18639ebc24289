#include "wavebench/analysis/speed_sweep.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "wavebench/analysis/poincare_section.hpp"
#include "wavebench/analysis/signal_channel.hpp"

namespace wavebench::analysis {

std::vector<double> sweep_speeds(const SweepOptions& o) {
  if (o.steps < 2) {
    throw std::invalid_argument("analysis.sweep.steps = " + std::to_string(o.steps) +
                                ": expected >= 2");
  }
  if (!(o.from_speed > 0) || !(o.to_speed > o.from_speed)) {
    throw std::invalid_argument(
        "analysis.sweep.from_speed/to_speed = " + std::to_string(o.from_speed) + "/" +
        std::to_string(o.to_speed) + " rad/s: expected 0 < from < to");
  }
  if (!(o.record_time > 0) || o.settle_time < 0) {
    throw std::invalid_argument("analysis.sweep.record_time = " + std::to_string(o.record_time) +
                                " s: expected > 0 (and settle_time >= 0)");
  }
  std::vector<double> speeds(static_cast<std::size_t>(o.steps));
  for (int i = 0; i < o.steps; ++i) {
    speeds[static_cast<std::size_t>(i)] =
        o.from_speed + (o.to_speed - o.from_speed) * i / (o.steps - 1);
  }
  return speeds;
}

model::KinematicInput sweep_trace(const std::vector<double>& speeds, double settle_time,
                                  double record_time, double ramp_time, double* total_time) {
  // Plateau per speed: ramp from the previous speed (linear in speed, so theta is quadratic),
  // the rest of the settle time, then the record window. PCHIP through the samples keeps the
  // speed continuous.
  model::KinematicInput in;
  double t = 0;
  double theta = 0;
  double previous = speeds.front();
  in.trace_t.push_back(0);
  in.trace_theta.push_back(0);
  constexpr int kRampPoints = 24;
  constexpr int kPlateauPoints = 4;
  for (std::size_t i = 0; i < speeds.size(); ++i) {
    const double w = speeds[i];
    const double ramp = i == 0 ? 0.0 : std::min(ramp_time, settle_time);
    for (int k = 1; k <= kRampPoints && ramp > 0; ++k) {
      const double s = ramp * k / kRampPoints;
      in.trace_t.push_back(t + s);
      in.trace_theta.push_back(theta + previous * s + 0.5 * (w - previous) / ramp * s * s);
    }
    if (ramp > 0) {
      theta += 0.5 * (previous + w) * ramp;
      t += ramp;
    }
    const double plateau = settle_time - ramp + record_time;
    for (int k = 1; k <= kPlateauPoints; ++k) {
      const double s = plateau * k / kPlateauPoints;
      in.trace_t.push_back(t + s);
      in.trace_theta.push_back(theta + w * s);
    }
    t += plateau;
    theta += w * plateau;
    previous = w;
  }
  in.speed = speeds.back();
  if (total_time) *total_time = t;
  return in;
}

std::vector<SweepJump> find_jumps(const std::vector<SweepPoint>& points,
                                  const std::string& direction, double threshold) {
  std::vector<SweepJump> jumps;
  for (std::size_t i = 1; i < points.size(); ++i) {
    const double a = points[i - 1].amplitude;
    const double b = points[i].amplitude;
    const double scale = std::max(std::abs(a), std::abs(b));
    if (!(scale > 0)) continue;
    const double change = std::abs(b - a) / scale;
    if (change > threshold) {
      jumps.push_back({direction, points[i - 1].speed, points[i].speed, a, b, change});
    }
  }
  return jumps;
}

void measure_hysteresis(SpeedSweep& sweep, double threshold) {
  sweep.max_hysteresis = 0;
  sweep.hysteresis_area = 0;
  sweep.hysteresis_speeds.clear();
  double last_speed = 0, last_diff = 0;
  bool have_last = false;
  // Pair the two sweeps speed by speed (down is stored descending).
  for (const auto& u : sweep.up) {
    const auto d = std::find_if(sweep.down.begin(), sweep.down.end(), [&](const SweepPoint& p) {
      return std::abs(p.speed - u.speed) <= 1e-9 * std::max(1.0, u.speed);
    });
    if (d == sweep.down.end()) continue;
    const double diff = std::abs(u.amplitude - d->amplitude);
    const double scale = std::max(std::abs(u.amplitude), std::abs(d->amplitude));
    const double relative = scale > 0 ? diff / scale : 0;
    if (relative > sweep.max_hysteresis) {
      sweep.max_hysteresis = relative;
      sweep.hysteresis_speed = u.speed;
    }
    if (relative > threshold) sweep.hysteresis_speeds.push_back(u.speed);
    if (have_last) sweep.hysteresis_area += 0.5 * (diff + last_diff) * (u.speed - last_speed);
    last_speed = u.speed;
    last_diff = diff;
    have_last = true;
  }
}

namespace {

std::vector<SweepPoint> sweep_once(const model::GearParams& params,
                                   const model::SimulationOptions& sim,
                                   const std::vector<double>& speeds, const SweepOptions& o,
                                   const std::string& signal, const model::TeTerm* strobe_term) {
  double total = 0;
  const double ramp = 0.25 * o.settle_time;
  model::GearParams p = params;
  p.input = sweep_trace(speeds, o.settle_time, o.record_time, ramp, &total);
  model::SimulationOptions options = sim;
  options.t_end = total;
  options.transient = 0;
  const model::SimulationResult result = model::simulate(p, options);
  const auto& r = result.response;
  const auto y = response_channel(r, signal);
  const double n = p.geometry.ratio;
  const double a = strobe_term ? strobe_term->order_input : 1.0;
  const double b = strobe_term ? strobe_term->order_output : 0.0;

  std::vector<SweepPoint> points;
  double window_end = 0;
  for (std::size_t i = 0; i < speeds.size(); ++i) {
    const double ramp_i = i == 0 ? 0.0 : std::min(ramp, o.settle_time);
    window_end += ramp_i + (o.settle_time - ramp_i) + o.record_time;
    const double window_start = window_end - o.record_time;
    const auto first = std::lower_bound(r.t.begin(), r.t.end(), window_start) - r.t.begin();
    const auto last = std::lower_bound(r.t.begin(), r.t.end(), window_end) - r.t.begin();
    SweepPoint point;
    point.speed = speeds[i];
    if (last - first >= 2) {
      const auto from = static_cast<std::size_t>(first);
      const auto count = static_cast<std::size_t>(last - first);
      const auto window = y.subspan(from, count);
      point.rms = rms_about_mean(window);
      const auto [lo, hi] = std::minmax_element(window.begin(), window.end());
      point.amplitude = 0.5 * (*hi - *lo);
      std::vector<double> phase(count);
      for (std::size_t k = 0; k < count; ++k) {
        const double theta1 = r.theta1[from + k];
        phase[k] = (a + b / n) * theta1 + b * r.te[from + k];
      }
      const auto section =
          strobe_on_phase(std::span<const double>(r.t).subspan(from, count), phase,
                          std::span<const double>(r.twist).subspan(from, count),
                          std::span<const double>(r.twist_rate).subspan(from, count));
      for (const auto& q : section.points) point.poincare_x.push_back(q.x);
    }
    points.push_back(std::move(point));
  }
  return points;
}

}  // namespace

SpeedSweep run_speed_sweep(const model::GearParams& params, const model::SimulationOptions& sim,
                           const SweepOptions& options, const std::string& signal,
                           const model::TeTerm* strobe_term) {
  SpeedSweep sweep;
  const auto up = sweep_speeds(options);
  std::vector<double> down(up.rbegin(), up.rend());
  sweep.up = sweep_once(params, sim, up, options, signal, strobe_term);
  sweep.down = sweep_once(params, sim, down, options, signal, strobe_term);
  sweep.jumps = find_jumps(sweep.up, "up", options.jump_threshold);
  const auto down_jumps = find_jumps(sweep.down, "down", options.jump_threshold);
  sweep.jumps.insert(sweep.jumps.end(), down_jumps.begin(), down_jumps.end());
  measure_hysteresis(sweep, options.jump_threshold);
  return sweep;
}

}  // namespace wavebench::analysis
