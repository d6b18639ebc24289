#pragma once
// What one run sends to the shared store: its index row, who and where, the figures the fleet
// queries (typed), the static table per direction and load, and the rest of results.json
// without its bulky arrays (traces, points, spectra: they stay in the run folder, which
// `samples_ref` names).

#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "wavebench/storage/run_store.hpp"

namespace wavebench::fleet {

struct StaticPassSummary {
  std::string direction;  // "forward" | "reverse"
  double load_nm = 0;
  std::optional<double> p2p_arcmin, mean_arcmin, std_arcmin;
};

struct RunSummary {
  std::string bench, run_id, station, operator_name, unit_serial, gear_model;
  std::string spec, spec_version;  // spec_version: SHA-256 (16 hex) of the spec as recorded
  std::string procedure, status, reason, verdict;
  std::optional<bool> pass;
  std::string started_at, finished_at;  // ISO 8601 UTC; finished_at empty when not finished
  std::string software_version, config_hash;
  std::string samples_ref;  // "<bench>:<run id>/samples.wbs": the samples stay on the bench
  // fleet_figures() name -> value; a figure the run did not measure is absent.
  std::map<std::string, double> figures;
  std::vector<StaticPassSummary> static_passes;
  nlohmann::json limits = nlohmann::json::object();   // run_limits key -> value
  nlohmann::json results = nlohmann::json::object();  // results.json less its bulky arrays
};

struct BenchIdentity {
  std::string bench;    // the fleet's name for the bench; empty: results.json's `bench`
  std::string station;  // may be empty
};

// From the index row and results.json as the run folder holds them (null or absent: a run
// that ended before it wrote results; the row alone then).
RunSummary summarise_run(const storage::RunRecord& run, const nlohmann::json& results,
                         const BenchIdentity& identity);

// The figure at a results.json value: a number, or an uncertain figure object's `value`.
std::optional<double> figure_value(const nlohmann::json& value);

}  // namespace wavebench::fleet
