#pragma once
// Running one procedure on a connected bench, as a recorded run (bench.md §4, §5; issue #5):
// the run folder is created in the RunStore, every sample goes to samples.wbs as it is
// acquired, the twin runs beside the bench, results.json (with the twin's residual) and the
// report are written at the end, and the run is finished complete or aborted with its reason.
//
// This is the one entry point the daemon and `wavebench run` share.

#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "wavebench/bench/bench.hpp"
#include "wavebench/procedures/product_spec.hpp"
#include "wavebench/procedures/settled_point.hpp"
#include "wavebench/storage/run_store.hpp"

namespace wavebench::procedures {

// results.json "schema": its format and major version (docs/formats/results.schema.json).
// Adding a key keeps it; removing, renaming or changing the meaning of one bumps the number.
inline constexpr const char* kResultsSchema = "wavebench.results/2";

struct RunRequest {
  std::string procedure;  // "static", "dynamic" or "lost-motion"
  // Procedure options (e.g. {"positions": 24, "loads_nm": [0, 60]} for static); missing keys
  // take the procedure's defaults. Validated before anything is created on disk.
  nlohmann::json options = nlohmann::json::object();
  std::string config_text;  // the bench config the run started with (copied, hashed)
  bool twin = true;         // run the twin beside the bench
  bool report = true;       // write report.html and its plots into the run folder
  // The product spec the run is accepted against (find_product_spec): its limits, with the
  // request's own "limits" on top, give the verdict; its lost_motion_at sets the lost-motion
  // procedure's lost_motion_fraction.
  std::optional<ProductSpec> spec;
  // Who and what: the serial of the unit under test (a barcode scanner types it; empty: the
  // bench config's unit_serial) and the operator (empty: not recorded). Checked by
  // check_run_identity().
  std::string unit_serial;
  std::string operator_name;
  // Called with each flag of the twin's diagnosis as results.json writes it (twin.diagnosis
  // .flags[]), live, on the twin's thread: never on the bench's, so it may lock and log.
  std::function<void(const nlohmann::json& flag)> on_diagnosis;
  // Called with each settled position of a static procedure as it is measured, on the bench
  // thread (SettledPointSink: quick, no I/O). Other procedures do not call it.
  SettledPointSink on_point;
};

// Throws std::invalid_argument naming `unit_serial` or `operator`, the value and what was
// expected: a serial is 1..64 of [A-Za-z0-9._/-]; an operator 1..64 printable characters
// without control characters or quotes.
void check_run_identity(const RunRequest& request);

struct RunProgress {
  std::string run_id;
  std::string phase;    // e.g. "static forward 0 N·m", "dynamic run-in", "twin calibration"
  double fraction = 0;  // 0..1 of the part reporting it: the recording, or the post-run work
  // Wall seconds left of that part, estimated from the procedure's plan and the pace so far
  // (recording) or from the record's length (post-run); negative: not known.
  double remaining_s = -1;
};

struct RunOutcome {
  std::string run_id;
  storage::RunStatus status = storage::RunStatus::kComplete;  // kComplete or kAborted
  std::string reason;                                         // why it was aborted
  nlohmann::json results;                                     // as written to results.json
  std::filesystem::path dir;
};

using ProgressSink = std::function<void(const RunProgress&)>;

// record_run() then RecordedRun::finish() beside the bench (recorded_run.hpp), in sequence:
// for callers with no next unit waiting (`wavebench run`, tests).
// Throws std::invalid_argument naming the option key, its value and what was expected when
// the request is bad (nothing is created then). A bench trip during the run is not an
// exception: the outcome is kAborted with the trip's reason, the data so far kept on disk.
RunOutcome execute_run(bench::Bench& bench, storage::RunStore& store, const RunRequest& request,
                       const ProgressSink& progress = {});

}  // namespace wavebench::procedures
