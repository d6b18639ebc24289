#pragma once
// Checking a run request before anything is built or created: the CLI and the daemon refuse a
// bad request (exit 2, HTTP 400) before they open a store or connect a bench.

#include "wavebench/runs/run_executor.hpp"

namespace wavebench::runs {

// Throws std::invalid_argument naming the option key, its value and what was expected; the
// same checks execute_run makes first.
void check_run_request(const RunRequest& request);

}  // namespace wavebench::runs
