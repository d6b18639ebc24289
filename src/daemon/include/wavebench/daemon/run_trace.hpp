#pragma once
// A stored run's curves for plots at any zoom, min/max per pixel column (min_max_columns.hpp):
//
//   GET /api/runs/{id}/trace?channels=te_arcsec,torque_nm&from_s=&to_s=&columns=
//       channels of samples.wbs against time from the log's first sample; full resolution
//       when the range holds no more than 2 x columns samples
//   GET /api/runs/{id}/twin?from_s=&to_s=&columns=
//       twin.csv (the twin beside the bench) and twin-calibrated.csv (the calibrated twin
//       replayed over the run), measured, predicted and residual TE
//
// Both stream their file in pages and keep at most a page and the decimated rows in memory,
// so a 10-minute run costs a bounded amount whatever the zoom. Bad parameters are 400 naming
// the key, the value and what was expected.

#include <filesystem>
#include <string>

#include "wavebench/daemon/daemon_api.hpp"
#include "wavebench/daemon/http_target.hpp"
#include "wavebench/storage/run_store.hpp"

namespace wavebench::daemon {

inline constexpr std::size_t kDefaultTraceColumns = 1000;
inline constexpr std::size_t kMaxTraceColumns = 4000;

// The run's id is checked to be in the store; `results` (for te_arcsec's gear sense) is read
// from the run folder.
ApiResponse run_trace(const storage::RunStore& store, const std::string& id,
                      const HttpTarget& target);
ApiResponse run_twin_trace(const storage::RunStore& store, const std::string& id,
                           const HttpTarget& target);

}  // namespace wavebench::daemon
