#pragma once
// A RunRequest read into its procedure and the run's own options (limits, twin calibration):
// shared by the request check and execute_run, which runs what the check accepted.

#include <nlohmann/json.hpp>

#include "procedure_registry.hpp"
#include "wavebench/procedures/run_executor.hpp"

namespace wavebench::procedures {

struct ParsedRequest {
  AnyProcedure procedure;
  nlohmann::json procedure_options;
  nlohmann::json limits = nlohmann::json::object();
  bool calibrate_twin = true;
  int repeats = 1;
};

// Throws std::invalid_argument naming the key, the value and what was expected.
ParsedRequest parse_request(const RunRequest& request);

}  // namespace wavebench::procedures
