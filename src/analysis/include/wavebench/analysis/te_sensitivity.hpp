#pragma once
// Sensitivity of the output vibration (RMS of the analysed signal) to each TE source's
// tolerance, and Monte-Carlo over tolerances and phases (seeds 000, 001: where to spend
// precision).
//
// Two estimates per source: `finite_difference` runs simulate() once per source with its
// amplitude raised by relative_step (the nonlinear model: backlash, impacts); `linear` uses the
// linearised transfer function (exact when the gear stays in contact). Monte-Carlo uses the
// linear transfer function only: thousands of simulate() runs would take hours.

#include <string>
#include <vector>

#include "wavebench/analysis/analysis_options.hpp"
#include "wavebench/analysis/linearised_gear.hpp"
#include "wavebench/model/simulation.hpp"

namespace wavebench::analysis {

struct SourceSensitivity {
  std::string source;
  double amplitude_rad = 0;
  double frequency_hz = 0;
  // d(RMS)/d(A) * A: the RMS change per 100 % of the tolerance, signal unit.
  double linear = 0;
  double finite_difference = 0;  // NaN when not run
  double rank_value = 0;         // what the ranking used (finite difference if run, else linear)
};

struct MonteCarloSummary {
  int runs = 0;
  unsigned seed = 0;
  double mean = 0, stddev = 0, p50 = 0, p95 = 0, max = 0;
  double nominal = 0;  // linear RMS at the nominal tolerances and phases
};

struct TeSensitivity {
  std::string signal;
  std::string method;                      // "finite differences (simulate) + linear" or "linear"
  double rms_nominal = 0;                  // of the simulated run
  double rms_linear = 0;                   // linear prediction at nominal tolerances
  std::vector<SourceSensitivity> sources;  // ranked, largest first
  MonteCarloSummary monte_carlo;
};

// RMS of the linear steady-state response to the terms (terms at one frequency add complex).
double linear_rms(const std::vector<model::TeTerm>& terms, const model::GearGeometry& geometry,
                  double mean_input_speed, const LinearGearCoefficients& linear,
                  const std::string& signal);

// Monte-Carlo: amplitudes uniform in [0, A_j] (a tolerance bounds the error), phases uniform.
MonteCarloSummary monte_carlo_linear(const std::vector<model::TeTerm>& terms,
                                     const model::GearGeometry& geometry, double mean_input_speed,
                                     const LinearGearCoefficients& linear,
                                     const std::string& signal, int runs, unsigned seed);

TeSensitivity te_sensitivity(const model::GearParams& params, const model::SimulationOptions& sim,
                             const SensitivityOptions& options, const std::string& signal,
                             double mean_input_speed, const LinearGearCoefficients& linear,
                             double rms_nominal, bool run_simulations);

}  // namespace wavebench::analysis
