#include "wavebench/model/solver/trajectory_runner.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <stdexcept>
#include <string>

namespace wavebench::model::solver {
namespace {

void require(bool ok, const char* key, double value, const char* expected) {
  if (!ok) {
    throw std::invalid_argument(std::string("trajectory option ") + key + " = " +
                                std::to_string(value) + ": expected " + expected);
  }
}

// A sign change from ga to gb; a witness that reaches exactly zero has crossed.
bool crosses(double ga, double gb) {
  return (ga < 0 && gb >= 0) || (ga > 0 && gb <= 0);
}

}  // namespace

TrajectoryRunner::TrajectoryRunner(Integrator& integrator, const OdeSystem& system,
                                   TrajectoryOptions options)
    : integrator_(integrator), system_(system), options_(std::move(options)) {
  const auto& o = options_;
  require(std::isfinite(o.t_end), "t_end", o.t_end, "a finite time [s]");
  require(std::isfinite(o.initial_step) && o.initial_step >= 0, "initial_step", o.initial_step,
          "a finite step >= 0 [s] (0 = automatic)");
  require(std::isfinite(o.sample_rate) && o.sample_rate >= 0, "sample_rate", o.sample_rate,
          "a finite rate >= 0 [Hz] (0 = no sampling)");
  require(std::isfinite(o.sample_t0), "sample_t0", o.sample_t0, "a finite time [s]");
  require(std::isfinite(o.event_tolerance) && o.event_tolerance > 0, "event_tolerance",
          o.event_tolerance, "a finite time > 0 [s]");
  require(std::isfinite(o.min_event_separation) && o.min_event_separation >= 0,
          "min_event_separation", o.min_event_separation, "a finite time >= 0 [s]");
  require(o.max_steps > 0, "max_steps", static_cast<double>(o.max_steps), "a count > 0");
  require(o.witness_probes >= 0 && o.witness_probes <= 64, "witness_probes",
          static_cast<double>(o.witness_probes), "a count in [0, 64]");
  require(std::isfinite(o.progress_interval) && o.progress_interval > 0, "progress_interval",
          o.progress_interval, "a fraction > 0");
}

void TrajectoryRunner::emit_samples_up_to(double t, std::span<const double> d,
                                          TrajectoryResult& result) {
  if (!(options_.sample_rate > 0)) return;
  for (;;) {
    // Each sample time from its index, so no rounding accumulates over millions of samples.
    const double ts = options_.sample_t0 + static_cast<double>(next_sample_) / options_.sample_rate;
    if (ts > t || ts > options_.t_end) return;
    if (sample_) {
      integrator_.dense_output(ts, y_dense_);
      sample_(ts, y_dense_, d);
    }
    ++next_sample_;
    ++result.samples;
  }
}

double TrajectoryRunner::locate_root(std::size_t k, double a, double ga, double b, double gb,
                                     std::span<const double> d, TrajectoryResult& result) {
  // Illinois (regula falsi that halves the stale end's value), with the trial point kept at
  // least tol/2 inside the bracket so the bracket itself, not only the residual, shrinks.
  const double tol = options_.event_tolerance;
  int side = 0;
  for (int iteration = 0; iteration < 200 && b - a > tol; ++iteration) {
    ++result.root_iterations;
    double c = (ga * b - gb * a) / (ga - gb);
    if (!std::isfinite(c)) c = 0.5 * (a + b);
    const double margin = 0.5 * tol;
    if (c < a + margin) c = a + margin;
    if (c > b - margin) c = b - margin;
    if (b - a <= 2 * margin || iteration % 8 == 7) c = 0.5 * (a + b);  // guarantee progress
    integrator_.dense_output(c, y_dense_);
    system_.witnesses(c, y_dense_, d, g_probe_);
    const double gc = g_probe_[k];
    if (crosses(ga, gc)) {
      b = c;
      gb = gc;
      if (side == -1) ga *= 0.5;
      side = -1;
    } else {
      a = c;
      ga = gc;
      if (side == +1) gb *= 0.5;
      side = +1;
    }
  }
  return b;
}

double TrajectoryRunner::find_crossings(double t_prev, double t, std::span<const double> d,
                                        TrajectoryResult& result) {
  const std::size_t m = g_prev_.size();
  // Probe times inside the step: evenly spaced witness_probes, plus one just after the start
  // when a witness sits exactly on zero there (right after its event): from zero alone the
  // sign it leaves with is unknown, and a ball that bounces and lands again inside one step
  // would show zero -> negative, no crossing.
  probe_t_.clear();
  bool zero_start = false;
  for (std::size_t k = 0; k < m; ++k) zero_start = zero_start || g_prev_[k] == 0;
  if (zero_start) probe_t_.push_back(t_prev + 1e-3 * (t - t_prev));
  const int probes = options_.witness_probes;
  for (int j = 1; j <= probes; ++j) {
    probe_t_.push_back(t_prev + (t - t_prev) * static_cast<double>(j) / (probes + 1));
  }
  const std::size_t p = probe_t_.size();
  for (std::size_t j = 0; j < p; ++j) {
    integrator_.dense_output(probe_t_[j], y_dense_);
    system_.witnesses(probe_t_[j], y_dense_, d, g_probe_);
    std::copy_n(g_probe_.begin(), m, probe_g_.begin() + static_cast<std::ptrdiff_t>(j * m));
  }
  double t_event = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < m; ++k) {
    root_t_[k] = std::numeric_limits<double>::infinity();
    // Walk t_prev, probes..., t and take the first sign change.
    double ta = t_prev, ga = g_prev_[k];
    for (std::size_t j = 0; j <= p; ++j) {
      const double tb = j < p ? probe_t_[j] : t;
      const double gb = j < p ? probe_g_[j * m + k] : g_new_[k];
      if (ga == 0) {
        ta = tb;
        ga = gb;
        continue;
      }
      if (crosses(ga, gb)) {
        const double tr = locate_root(k, ta, ga, tb, gb, d, result);
        if (tr < last_event_t_[k] + options_.min_event_separation) {
          ++result.suppressed_events;
        } else {
          root_t_[k] = tr;
          root_direction_[k] = ga < 0 ? +1 : -1;
          t_event = std::min(t_event, tr);
        }
        break;
      }
      ta = tb;
      ga = gb;
    }
  }
  return t_event;
}

TrajectoryResult TrajectoryRunner::run(double t0, std::span<double> y, std::span<double> d) {
  const auto& o = options_;
  if (!(o.t_end >= t0)) {
    throw std::invalid_argument("TrajectoryRunner: t_end = " + std::to_string(o.t_end) +
                                " lies before t0 = " + std::to_string(t0));
  }
  const std::size_t n = system_.continuous_size();
  if (y.size() != n || d.size() != system_.discrete_size()) {
    throw std::invalid_argument("TrajectoryRunner: state sizes " + std::to_string(y.size()) + "/" +
                                std::to_string(d.size()) + " do not match the system's " +
                                std::to_string(n) + "/" + std::to_string(system_.discrete_size()));
  }
  const std::size_t m = o.locate_events ? system_.witness_count() : 0;
  y_dense_.assign(n, 0.0);
  g_prev_.assign(m, 0.0);
  g_new_.assign(m, 0.0);
  g_probe_.assign(system_.witness_count(), 0.0);
  last_event_t_.assign(m, -std::numeric_limits<double>::infinity());
  root_t_.assign(m, 0.0);
  root_direction_.assign(m, 0);
  probe_t_.reserve(static_cast<std::size_t>(o.witness_probes) + 1);
  probe_g_.assign((static_cast<std::size_t>(o.witness_probes) + 1) * m, 0.0);

  TrajectoryResult result;
  integrator_.initialize(system_, t0, y, d, o.initial_step);

  if (o.sample_rate > 0) {
    // The first sample is at sample_t0, or the first grid point after t0 if that is later.
    std::int64_t k = 0;
    if (t0 > o.sample_t0) {
      k = static_cast<std::int64_t>(std::ceil((t0 - o.sample_t0) * o.sample_rate));
      while (k > 0 && o.sample_t0 + static_cast<double>(k - 1) / o.sample_rate >= t0) --k;
      while (o.sample_t0 + static_cast<double>(k) / o.sample_rate < t0) ++k;
    }
    next_sample_ = k;
    emit_samples_up_to(t0, d, result);
  }
  if (m > 0) {
    // The full witness vector goes into g_probe_, then the located ones are copied.
    system_.witnesses(t0, y, d, g_probe_);
    std::copy_n(g_probe_.begin(), m, g_prev_.begin());
  }

  const double span = o.t_end - t0;
  double next_progress = o.progress_interval;
  std::int64_t steps = 0;
  double t = t0;
  while (t < o.t_end) {
    if (steps >= o.max_steps) {
      throw std::runtime_error(
          "TrajectoryRunner: max_steps = " + std::to_string(o.max_steps) +
          " accepted steps reached at t = " + std::to_string(t) + " of [" + std::to_string(t0) +
          ", " + std::to_string(o.t_end) + "] (" + std::to_string(result.events.size()) +
          " events); the step size collapsed — a stiff problem needs the Rosenbrock method");
    }
    const double t_prev = integrator_.current_time();
    t = integrator_.step(o.t_end);
    ++steps;

    bool event_fired = false;
    if (m > 0) {
      system_.witnesses(t, integrator_.current_state(), d, g_probe_);
      std::copy_n(g_probe_.begin(), m, g_new_.begin());
      const double t_event = find_crossings(t_prev, t, d, result);
      if (t_event < std::numeric_limits<double>::infinity()) {
        emit_samples_up_to(t_event, d, result);
        std::vector<double>& y_event = y_dense_;
        integrator_.dense_output(t_event, y_event);
        // Witnesses whose roots lie within the tolerance of the earliest fire together, in
        // index order, as one restart of the integrator.
        for (std::size_t k = 0; k < m; ++k) {
          if (root_t_[k] > t_event + o.event_tolerance) continue;
          system_.on_event(k, t_event, y_event, d);
          result.events.push_back({t_event, k, root_direction_[k]});
          last_event_t_[k] = t_event;
        }
        integrator_.reset(t_event, y_event);
        t = t_event;
        system_.witnesses(t, integrator_.current_state(), d, g_probe_);
        std::copy_n(g_probe_.begin(), m, g_prev_.begin());
        event_fired = true;
      } else {
        g_prev_.swap(g_new_);
      }
    }
    if (!event_fired) emit_samples_up_to(t, d, result);

    if (progress_ && span > 0) {
      const double fraction = (t - t0) / span;
      if (fraction >= next_progress && fraction < 1.0) {
        progress_(fraction);
        next_progress = fraction + o.progress_interval;
      }
    }
  }
  if (progress_) progress_(1.0);

  const auto final_state = integrator_.current_state();
  std::copy(final_state.begin(), final_state.end(), y.begin());
  result.counters = integrator_.counters();  // initialize() started them from zero
  result.t_final = t;
  return result;
}

}  // namespace wavebench::model::solver
