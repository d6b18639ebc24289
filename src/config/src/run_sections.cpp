// solver and analysis: how to integrate a case and what to compute from the response.
#include <string>

#include "twin_sections.hpp"
#include "wavebench/config/config_error.hpp"

namespace wavebench::config {

void parse_solver_section(YamlSection& s, model::SimulationOptions& solver) {
  const std::string method = s.choice_or("method", {"dopri5", "rk4", "rosenbrock"}, "dopri5");
  solver.method = method == "rk4"          ? model::SolverMethod::kRk4
                  : method == "rosenbrock" ? model::SolverMethod::kRosenbrock4
                                           : model::SolverMethod::kDormandPrince45;
  // Tolerances below these ask for more digits than a double has: the step would shrink
  // towards zero and the run would never end.
  if (s.has("rtol")) {
    solver.rtol = s.positive_quantity("rtol", Dimension::kDimensionless);
    s.require_within("rtol", solver.rtol, 1e-12, 0.5, "a relative tolerance");
  }
  if (s.has("atol")) {
    solver.atol = s.positive_quantity("atol", Dimension::kDimensionless);
    s.require_within("atol", solver.atol, 1e-14, 1.0, "an absolute tolerance");
  }
  if (s.has("t_end")) {
    solver.t_end = s.positive_quantity("t_end", Dimension::kTime);
    s.require_within("t_end", solver.t_end, kMinTwinSimulatedS, kMaxTwinSimulatedS,
                     "a simulated time [s]");
  }
  solver.transient = s.non_negative_quantity_or("transient", Dimension::kTime, solver.transient);
  if (!(solver.transient < solver.t_end)) {
    s.fail("transient", s.value_text("transient"),
           "a transient shorter than t_end (" + std::to_string(solver.t_end) + " s)");
  }
  if (s.has("sample_rate")) {
    solver.sample_rate = s.positive_quantity("sample_rate", Dimension::kFrequency);
    s.require_within("sample_rate", solver.sample_rate, 1.0, 10e6, "an output rate [Hz]");
  }
  if (s.has("fixed_step")) {
    solver.fixed_step = s.positive_quantity("fixed_step", Dimension::kTime);
    s.require_within("fixed_step", solver.fixed_step, 1e-8, 1.0, "a step [s]");
  }
  solver.max_step = s.non_negative_quantity_or("max_step", Dimension::kTime, solver.max_step);
  if (solver.max_step > 0) {
    s.require_within("max_step", solver.max_step, 1e-8, kMaxTwinSimulatedS,
                     "0 (no limit) or a step [s]");
  }
  solver.locate_events = s.boolean_or("locate_events", solver.locate_events);
  s.finish();
}

namespace {

void parse_spectrum(YamlSection& s, analysis::SpectrumOptions& o) {
  o.signal = s.choice_or("signal",
                         {"alpha2", "omega2", "theta2_dev", "te", "twist", "twist_rate",
                          "gear_torque", "omega1", "load_torque", "motor_torque"},
                         o.signal);
  const std::string window = s.choice_or("window", {"hann", "flattop", "rectangular"}, "hann");
  o.window = window == "flattop"       ? analysis::Window::kFlatTop
             : window == "rectangular" ? analysis::Window::kRectangular
                                       : analysis::Window::kHann;
  o.max_frequency_hz =
      s.non_negative_quantity_or("max_frequency", Dimension::kFrequency, o.max_frequency_hz);
  // 0 = up to Nyquist; above the largest output rate (10 MHz) it means the same.
  s.require_within("max_frequency", o.max_frequency_hz, 0, 10e6, "a frequency [Hz]");
  o.max_peaks = static_cast<int>(s.integer_or("max_peaks", kIntMin, kIntMax, o.max_peaks));
  s.require_within("max_peaks", o.max_peaks, 1, 1000, "a number of peaks");
  o.min_relative_amplitude = s.non_negative_quantity_or(
      "min_relative_amplitude", Dimension::kDimensionless, o.min_relative_amplitude);
  // A fraction of the largest line: above 1 every peak, the largest too, would be dropped.
  s.require_within("min_relative_amplitude", o.min_relative_amplitude, 0, 1,
                   "a fraction of the largest line");
  s.finish();
}

void parse_sweep(YamlSection& s, analysis::SweepOptions& o) {
  o.enabled = s.boolean_or("enabled", true);
  o.from_speed = s.positive_quantity("from", Dimension::kAngularSpeed);
  o.to_speed = s.positive_quantity("to", Dimension::kAngularSpeed);
  o.steps = static_cast<int>(s.integer("steps", kIntMin, kIntMax));
  s.require_within("steps", o.steps, 2, 1000, "a number of sweep speeds");
  s.require_within("from", o.from_speed, 0, kMaxSpeedRadS, "a speed [rad/s]");
  s.require_within("to", o.to_speed, 0, kMaxSpeedRadS, "a speed [rad/s]");
  o.settle_time = s.positive_quantity("settle_time", Dimension::kTime);
  s.require_within("settle_time", o.settle_time, 0, kMaxTwinSimulatedS, "a time [s]");
  o.record_time = s.positive_quantity("record_time", Dimension::kTime);
  s.require_within("record_time", o.record_time, 0, kMaxTwinSimulatedS, "a time [s]");
  o.jump_threshold =
      s.non_negative_quantity_or("jump_threshold", Dimension::kDimensionless, o.jump_threshold);
  // A relative change between neighbouring speeds: 100 (10 000 %) is a jump of any sense.
  s.require_within("jump_threshold", o.jump_threshold, 0, 100, "a relative amplitude change");
  s.finish();
}

}  // namespace

void parse_analysis_section(YamlSection& s, analysis::AnalysisOptions& analysis) {
  if (auto sp = s.optional_section("spectrum")) parse_spectrum(*sp, analysis.spectrum);
  analysis.order_spectrum = s.boolean_or("order_spectrum", analysis.order_spectrum);
  if (auto p = s.optional_section("poincare")) {
    analysis.poincare.excitation_source = p->text_or("excitation_source", "");
    analysis.poincare.max_clusters = static_cast<int>(
        p->integer_or("max_clusters", kIntMin, kIntMax, analysis.poincare.max_clusters));
    p->require_within("max_clusters", analysis.poincare.max_clusters, 1, 1000,
                      "a number of clusters");
    p->finish();
  }
  if (auto sw = s.optional_section("sweep")) parse_sweep(*sw, analysis.sweep);
  if (auto se = s.optional_section("sensitivity")) {
    auto& o = analysis.sensitivity;
    o.enabled = se->boolean_or("enabled", true);
    o.relative_step = se->quantity_or("relative_step", Dimension::kDimensionless, o.relative_step);
    if (!(o.relative_step > 0)) {
      se->fail("relative_step", se->value_text("relative_step"), "a fraction > 0");
    }
    se->require_within("relative_step", o.relative_step, 0, 1, "a fraction");
    o.monte_carlo_runs =
        static_cast<int>(se->integer_or("monte_carlo_runs", kIntMin, kIntMax, o.monte_carlo_runs));
    se->require_within("monte_carlo_runs", o.monte_carlo_runs, 0, 100000, "a number of runs");
    const int seed = static_cast<int>(se->integer_or("seed", kIntMin, kIntMax, o.seed));
    if (seed < 0) se->fail("seed", se->value_text("seed"), "an integer >= 0");
    o.seed = static_cast<unsigned>(seed);
    se->finish();
  }
  analysis.linearise = s.boolean_or("linearise", analysis.linearise);
  s.finish();
}

}  // namespace wavebench::config
