#pragma once
// The shared results store of a lab: every bench publishes its finished runs to it, quality
// engineering asks across benches (runs of a gear model, a figure's trend, its SPC). The run
// folders and the bench's own SQLite index stay the record of each bench; this holds summaries.

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "wavebench/fleet/run_summary.hpp"
#include "wavebench/fleet/spc.hpp"

namespace wavebench::fleet {

struct FleetRunQuery {
  std::optional<std::string> gear_model, bench, unit_serial, procedure, spec, verdict, status;
  std::optional<std::string> unit_serial_prefix;  // units whose serial starts with it
  std::optional<std::string> from, to;            // started_at bounds, ISO 8601 (inclusive)
  int limit = 50;                                 // newest first
};

struct FleetRunRow {
  std::string bench, run_id, station, operator_name, unit_serial, gear_model, spec, spec_version;
  std::string procedure, status, verdict, started_at, finished_at, software_version, samples_ref;
  nlohmann::json figures = nlohmann::json::object();
};

// One figure of complete runs of one gear model, oldest first.
struct FigureQuery {
  std::string figure;      // a fleet_figures() name
  std::string gear_model;  // required: a trend mixes no models
  std::optional<std::string> bench;
  // static_te_p2p only: one pass of the static table instead of the run's largest.
  std::optional<std::string> direction;
  std::optional<double> load_nm;
  std::optional<std::string> from, to;
  int last = 0;  // only the newest N runs (0: all)
};

struct TrendPoint {
  int sequence = 0;  // 1 = the oldest in the answer (the unit sequence)
  std::string started_at, bench, run_id, unit_serial;
  double value = 0;
};

struct SpcAnswer {
  std::vector<TrendPoint> points;
  SpecLimits limits;
  std::string limits_from;  // "spec <name> (<version>)", "command line", or "none"
  SpcFigures figures;
};

class ResultsStore {
 public:
  virtual ~ResultsStore() = default;
  // Idempotent by (bench, run id): a run published again changes nothing. Returns whether
  // this call inserted it. Throws std::runtime_error when the store cannot be reached.
  virtual bool publish(const RunSummary& run) = 0;
  virtual std::vector<FleetRunRow> runs(const FleetRunQuery& query) = 0;
  virtual std::vector<TrendPoint> trend(const FigureQuery& query) = 0;
  // The trend's values and the spec limits of the newest run's spec (unless `limits` gives
  // one), with the SPC figures over them.
  virtual SpcAnswer spc(const FigureQuery& query, const SpecLimits& limits) = 0;
};

nlohmann::json to_json(const FleetRunRow& row);
nlohmann::json to_json(const TrendPoint& point);
nlohmann::json to_json(const SpcAnswer& answer);

}  // namespace wavebench::fleet
