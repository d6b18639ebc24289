#pragma once
// The analysis of one twin run (model.md §9): spectrum with attributed peaks, order spectrum,
// phase portrait and Poincare section with the motion class, linearised model, and optionally
// a speed sweep and TE sensitivity (these call simulate() again).

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "wavebench/analysis/amplitude_spectrum.hpp"
#include "wavebench/analysis/analysis_options.hpp"
#include "wavebench/analysis/linearised_gear.hpp"
#include "wavebench/analysis/motion_classifier.hpp"
#include "wavebench/analysis/order_spectrum.hpp"
#include "wavebench/analysis/peak_attribution.hpp"
#include "wavebench/analysis/poincare_section.hpp"
#include "wavebench/analysis/speed_sweep.hpp"
#include "wavebench/analysis/te_sensitivity.hpp"
#include "wavebench/model/simulation.hpp"

namespace wavebench::analysis {

struct TwinAnalysis {
  std::string signal;           // channel analysed (AnalysisOptions::spectrum.signal)
  double mean_input_speed = 0;  // [rad/s] mean of omega1
  double sample_rate_hz = 0;
  AmplitudeSpectrum spectrum;         // of `signal`
  std::vector<AttributedPeak> peaks;  // largest first
  std::optional<OrderSpectrum> orders;
  PhasePortrait portrait;  // Delta vs Delta'
  PoincareSection poincare;
  MotionClassification motion;
  std::optional<LinearisedGear> linear;
  std::optional<SpeedSweep> sweep;
  std::optional<TeSensitivity> sensitivity;
  double rms = 0;  // of `signal`, mean removed
};

TwinAnalysis analyse_twin_run(const model::GearParams& params,
                              const model::SimulationOptions& sim_options,
                              const model::SimulationResult& result,
                              const AnalysisOptions& options);

// Keys: signal, mean_input_speed_rad_s, rms, spectrum {resolution_hz, sample_rate_hz, window,
// samples}, peaks [{freq_hz, amplitude, predicted_amplitude, aliased, label, sources [{source,
// share, in_phase_share, term_freq_hz, aliased}]}], orders {resolution, peaks [{order_input,
// order_output, amplitude}]}, motion {class, clusters, period, spread, correlation_dimension,
// lyapunov_per_period, points, evidence}, natural_frequencies_hz, modes, damping_ratios,
// mean_stiffness, sweep {...}, sensitivity {...}, sim_time_s, steps, rejected_steps,
// rhs_evaluations, events, wall_s.
nlohmann::json summary_json(const TwinAnalysis& analysis, const model::SimulationResult& result);

}  // namespace wavebench::analysis
