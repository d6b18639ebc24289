#pragma once
// Writes a twin case back as YAML in the schema of configs/twin/README.md, so that
// load_twin_case() reads the same parameters again (the calibrated twin config of a run).
// Values are written in SI with 17 significant digits: a round trip is exact.

#include <string>

#include "wavebench/config/twin_case.hpp"

namespace wavebench::config {

// `comment` (may be multi-line) goes at the top of the file as YAML comments. The analysis
// section is not written (the loader's defaults apply).
// The config's name of a TE family (`family:` in a twin case): "tangential_output", ...
const char* te_family_name(model::TeFamily family);

std::string write_twin_case_yaml(const TwinCase& twin, const std::string& comment = "");

}  // namespace wavebench::config
