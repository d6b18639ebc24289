#pragma once
// The request check as execute_run uses it: one parse, the same one the check accepted.

#include "parsed_request.hpp"
#include "wavebench/procedures/run_request_check.hpp"

namespace wavebench::procedures {

// check_run_request that also hands back what it parsed.
ParsedRequest check_and_parse(const RunRequest& request, const bench::BenchDescription& bench,
                              std::size_t extra_channels, const RunBudget& budget,
                              RunEstimate* estimate = nullptr);

}  // namespace wavebench::procedures
