// The budgets of a twin run, checked from the config alone: a typo in t_end or sample_rate
// must be refused in milliseconds, not found by the kernel's OOM killer an hour later.
#include <cmath>
#include <cstdio>
#include <string>

#include "wavebench/config/config_error.hpp"
#include "wavebench/config/twin_case.hpp"

namespace wavebench::config {
namespace {

// Peak memory per output sample: 12 response channels, the analysis' copies (window, FFT,
// strobe phase, order resampling) and the plot series. Measured as peak RSS / samples of the
// XB-80 case at 60 kHz (see tests/hostile): about 230 bytes; rounded up.
constexpr double kBytesPerOutputSample = 256;

std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", v);
  return buf;
}

std::string bytes(double b) {
  const char* units[] = {"bytes", "KiB", "MiB", "GiB", "TiB"};
  int u = 0;
  while (b >= 1024 && u < 4) {
    b /= 1024;
    ++u;
  }
  char buf[48];
  if (u == 4 && b >= 1024) {
    std::snprintf(buf, sizeof buf, "%.3g TiB", b);
  } else {
    std::snprintf(buf, sizeof buf, "%.2g %s", b, units[u]);
    if (b >= 10) std::snprintf(buf, sizeof buf, "%.0f %s", b, units[u]);
  }
  return buf;
}

std::string hertz(double f) {
  if (f >= 1e6) return number(f / 1e6) + " MHz";
  if (f >= 1e3) return number(f / 1e3) + " kHz";
  return number(f) + " Hz";
}

std::string seconds(double s) {
  return number(s) + " s";
}

}  // namespace

TwinRunEstimate estimate_twin_run(const TwinCase& twin) {
  const auto& s = twin.solver;
  TwinRunEstimate e;
  const double record = std::max(0.0, s.t_end - s.transient);
  e.output_samples = record * s.sample_rate + 2;
  const auto& sw = twin.analysis.sweep;
  if (sw.enabled) {
    // The sweep keeps one point's record at a time, beside the main run's.
    e.output_samples =
        std::max(e.output_samples, e.output_samples + sw.record_time * s.sample_rate);
  }
  e.output_bytes = e.output_samples * kBytesPerOutputSample;
  e.simulated_s = s.t_end + (sw.enabled ? 2.0 * sw.steps * (sw.settle_time + sw.record_time) : 0);
  if (s.method == model::SolverMethod::kRk4) {
    e.steps = e.simulated_s / s.fixed_step;
  } else if (s.max_step > 0) {
    e.steps = e.simulated_s / s.max_step;
  }
  return e;
}

void check_twin_run_budget(const TwinCase& twin, const std::string& t_end_key) {
  const auto& s = twin.solver;
  const TwinRunEstimate e = estimate_twin_run(twin);
  const bool sweep = twin.analysis.sweep.enabled;
  if (e.simulated_s > kMaxTwinSimulatedS) {
    if (sweep && s.t_end <= kMaxTwinSimulatedS) {
      throw ConfigError("analysis.sweep.steps", std::to_string(twin.analysis.sweep.steps),
                        "a sweep that simulates at most " + seconds(kMaxTwinSimulatedS) +
                            " with t_end (this one: " + seconds(e.simulated_s) + ")");
    }
    throw ConfigError(t_end_key, seconds(s.t_end),
                      "a simulated time of at most " + seconds(kMaxTwinSimulatedS));
  }
  if (e.output_bytes > kMaxTwinOutputBytes) {
    throw ConfigError(t_end_key, seconds(s.t_end),
                      "a run whose output fits in " + bytes(kMaxTwinOutputBytes) +
                          " (this one needs " + bytes(e.output_bytes) + " at " +
                          hertz(s.sample_rate) +
                          " output: shorten t_end or lower solver.sample_rate)");
  }
  if (e.steps > kMaxTwinSteps) {
    const bool rk4 = s.method == model::SolverMethod::kRk4;
    const std::string key = rk4 ? "solver.fixed_step" : "solver.max_step";
    const double step = rk4 ? s.fixed_step : s.max_step;
    throw ConfigError(key, seconds(step),
                      "a step that needs at most " + number(kMaxTwinSteps) + " steps for " +
                          seconds(e.simulated_s) + " simulated (this one needs " + number(e.steps) +
                          ": a longer step or a shorter " + t_end_key + ")");
  }
}

}  // namespace wavebench::config
