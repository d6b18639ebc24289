#pragma once
// GET /api/runs: the query parameters of the run history read into a RunQuery, and the page.
//
//   unit, procedure, spec, verdict (pass|fail|none), status, from, to, offset, limit
//
// from/to are ISO dates (2026-11-24), ISO UTC times (2026-11-24T10:30:00Z) or run ids, both
// inclusive (to=2026-11-24 includes that whole day); limit defaults to 50, at most 1000.

#include <cstddef>
#include <map>
#include <nlohmann/json.hpp>
#include <string>

#include "wavebench/storage/run_store.hpp"

namespace wavebench::daemon {

inline constexpr int kDefaultHistoryLimit = 50;
inline constexpr int kMaxHistoryLimit = 1000;

// Throws std::invalid_argument naming the key, the value and what was expected.
storage::RunQuery parse_run_history_query(const std::map<std::string, std::string>& query);

// {"runs": [run, ...] newest first, "total": runs matching, "offset", "limit"}
nlohmann::json run_history_page(const storage::RunStore& store, const storage::RunQuery& query);

}  // namespace wavebench::daemon
