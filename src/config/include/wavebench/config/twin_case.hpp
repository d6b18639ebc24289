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

// The same from YAML text; `source` names it in error messages.
TwinCase parse_twin_case(const std::string& yaml_text, const std::string& source = "<string>");

}  // namespace wavebench::config
