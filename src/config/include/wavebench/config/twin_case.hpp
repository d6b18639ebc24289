#pragma once
// A twin case: the gear, how to solve it and what to analyse, read from a YAML file
// (configs/twin/*.yaml). Values may carry units; everything here is SI.

#include <filesystem>
#include <string>

#include "wavebench/analysis/analysis_options.hpp"
#include "wavebench/model/gear_params.hpp"
#include "wavebench/model/simulation.hpp"

namespace wavebench::config {

struct TwinCase {
  model::GearParams gear;
  model::SimulationOptions solver;
  analysis::AnalysisOptions analysis;
};

// Throws ConfigError (key, value, expected; attributed to the file) on any problem: a missing
// required key, an unknown key, an unknown or wrong unit, a non-finite or out-of-range value,
// a ratio that disagrees with the tooth counts.
TwinCase load_twin_case(const std::filesystem::path& path);

// What a run of a case needs, estimated from t_end, the step, the output sample rate and the
// analysis before anything is allocated.
struct TwinRunEstimate {
  double output_samples = 0;  // per channel, after the transient
  double output_bytes = 0;    // the response, the analysis' copies of it and the CSV rows
  double steps = 0;           // a lower bound: t_end / fixed_step (rk4) or t_end / max_step
  double simulated_s = 0;     // t_end plus the sweep's runs
};
TwinRunEstimate estimate_twin_run(const TwinCase& twin);

inline constexpr double kMaxTwinOutputBytes = 2.0 * 1024 * 1024 * 1024;  // 2 GiB
inline constexpr double kMaxTwinSteps = 50e6;       // about a minute of the XB-80 case's steps
inline constexpr double kMaxTwinSimulatedS = 3600;  // t_end plus a sweep's runs
// A microsecond holds a few steps of the fastest case; shorter is no run (1e-300 s left nothing
// to analyse and failed without naming --t-end).
inline constexpr double kMinTwinSimulatedS = 1e-6;

// Throws ConfigError when the estimate is beyond a budget, naming the key to change and the
// numbers. `t_end_key` is how the user gave t_end ("solver.t_end", or "--t-end" on the CLI).
void check_twin_run_budget(const TwinCase& twin, const std::string& t_end_key = "solver.t_end");

// The same from YAML text; `source` names it in error messages.
TwinCase parse_twin_case(const std::string& yaml_text, const std::string& source = "<string>");

// Throws ConfigError naming the case's keys behind the first channel of `response` that is
// not finite (twin_response_check.cpp).
void check_finite_response(const model::SampledResponse& response);

}  // namespace wavebench::config
