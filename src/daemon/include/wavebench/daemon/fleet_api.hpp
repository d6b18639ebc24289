#pragma once
// GET /api/fleet/runs|trend|spc: the lab's shared results store (else the bench's own) through
// the daemon, the same queries as `wavebench fleet` (query parameters named as its options:
// model, bench, unit, procedure, verdict, from, to, limit; figure, direction, load, last; lsl,
// usl). Each request opens its own connection (the API's threads share none), on the
// low-priority read threads.

#include <filesystem>
#include <functional>

#include "wavebench/daemon/daemon_api.hpp"
#include "wavebench/daemon/http_target.hpp"
#include "wavebench/fleet/results_config.hpp"

namespace wavebench::daemon {

using FleetQueries = std::function<ApiResponse(const HttpTarget& target)>;

// Answers 400 naming a bad parameter, 503 when the store cannot be reached, 404 for an unknown
// query. A shared (postgresql) `config` queries that server; a sqlite one this bench's own
// store in `own_index` (the run store's index.sqlite).
FleetQueries make_fleet_queries(fleet::ResultsConfig config, std::filesystem::path own_index);

}  // namespace wavebench::daemon
