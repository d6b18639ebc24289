#pragma once
// What one run carries from its recording (on the bench thread) to its post-run stages (on
// the post-run worker): the request as parsed, the run folder, the results so far, the twin
// that ran beside the bench. One context per run, handed from stage to stage.

#include <chrono>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "parsed_request.hpp"
#include "wavebench/bench/bench_description.hpp"
#include "wavebench/metrology/static_te_statistics.hpp"
#include "wavebench/procedures/finished_figures.hpp"
#include "wavebench/procedures/run_executor.hpp"
#include "wavebench/twin/twin_beside_bench.hpp"
#include "wavebench/twin/twin_calibrator.hpp"

namespace wavebench::procedures {

struct ProcedureResult {
  nlohmann::json json = nlohmann::json::object();
  std::optional<metrology::StaticTeResult> static_result;
};

struct RunContext {
  explicit RunContext(ParsedRequest p) : parsed(std::move(p)) {}

  RunRequest request;  // on_diagnosis cleared once recording ends (its owner may be gone)
  ParsedRequest parsed;
  bench::BenchDescription description;
  storage::RunStore* store = nullptr;
  storage::RunPaths paths;
  std::string unit_serial;
  std::uint64_t samples = 0;  // in samples.wbs, for the post-run estimates

  RunOutcome outcome;  // status kAborted once abort_with() was called
  nlohmann::json results = nlohmann::json::object();
  ProcedureResult procedure_result;
  // What the procedure had finished by its last part: results.json's sections of a run that
  // did not complete (issue #22).
  std::optional<FinishedFigures> finished;

  // The twin beside the bench: the unit's own when it had one at the run's start, else the
  // bench's nominal twin case.
  model::GearParams twin_gear;
  twin::TwinSolverOptions twin_solver;
  nlohmann::json twin_source;
  std::unique_ptr<twin::TwinBesideBench> twin_beside;
  nlohmann::json twin_json;
  std::optional<twin::TwinCalibration> calibration;  // the twin fitted to this run alone
  std::optional<bool> pass;
  std::optional<metrology::LimitDecision> decision;

  void abort_with(const std::string& reason) {
    if (outcome.status == storage::RunStatus::kAborted) return;  // the first reason stands
    outcome.status = storage::RunStatus::kAborted;
    outcome.reason = reason;
  }
  bool complete() const { return outcome.status == storage::RunStatus::kComplete; }
};

}  // namespace wavebench::procedures
