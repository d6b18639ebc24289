#include "post_run_stages.hpp"

#include <array>
#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <system_error>

#include "wavebench/report/run_report.hpp"
#include "wavebench/procedures/run_limits.hpp"
#include "wavebench/storage/atomic_file.hpp"
#include "wavebench/storage/sample_log.hpp"
#include "wavebench/twin/twin_overlay.hpp"
#include "wavebench/twin/unit_twin_store.hpp"

namespace wavebench::procedures {

namespace {

// Wall seconds of each stage, measured on the simulated bench (2 cores shared with other
// builds; results.json "timing" of static and dynamic runs: static calibration 5.0e-4 s per
// sample, dynamic 2.2e-4 to 3.4e-4, unit twin 2.9e-4 per record replayed, report under 2 s),
// the slowest seen, times a margin: the worker runs at nice 19 beside the next recording.
constexpr double kMargin = 1.5;
constexpr double kTwinDrainS = 0.5;             // the backlog the twin has left
constexpr double kResultsS = 0.3;               // results.json, index row
constexpr double kUnitTwinPerSampleS = 3.0e-4;  // each record the unit twin replays
constexpr double kReportPerSampleS = 1.5e-5;    // plots over the record
constexpr double kReportS = 1.0;
constexpr std::uint64_t kSampleBytesEstimate = 100;  // a samples.wbs record, roughly

// The calibration's cost per sample: a static run's fit also takes its settled positions.
double calibration_per_sample_s(const std::string& procedure) {
  constexpr double kStaticPerSampleS = 5.0e-4;
  constexpr double kOtherPerSampleS = 3.4e-4;
  return procedure == "static" ? kStaticPerSampleS : kOtherPerSampleS;
}

bool calibrates(const RunContext& c) {
  return c.twin_beside && c.parsed.calibrate_twin && c.complete();
}

double estimate_twin(const RunContext& c) {
  return c.twin_beside ? kMargin * kTwinDrainS : 0;
}

double estimate_calibration(const RunContext& c) {
  if (!calibrates(c)) return 0;
  const auto n = std::min<std::uint64_t>(c.samples, twin::kMaxCalibrationSamples);
  return kMargin * calibration_per_sample_s(c.request.procedure) * static_cast<double>(n);
}

double estimate_verdict(const RunContext&) {
  return 0;
}
double estimate_results(const RunContext&) {
  return kMargin * kResultsS;
}

// The unit twin replays the unit's newest complete run of each procedure: their records on
// disk now, this run's in place of its own procedure's.
double estimate_unit_twin(const RunContext& c) {
  if (!calibrates(c) || c.unit_serial.empty()) return 0;
  std::uint64_t samples = std::min<std::uint64_t>(c.samples, twin::kMaxCalibrationSamples);
  try {
    storage::RunQuery q;
    q.unit_serial = c.unit_serial;
    q.status = storage::RunStatus::kComplete;
    q.limit = 200;
    std::vector<std::string> seen{c.request.procedure};
    for (const auto& r : c.store->list_runs(q)) {
      if (std::find(seen.begin(), seen.end(), r.procedure) != seen.end()) continue;
      seen.push_back(r.procedure);
      std::error_code ec;
      const auto bytes = std::filesystem::file_size(c.store->paths(r.id).samples, ec);
      if (!ec) {
        samples +=
            std::min<std::uint64_t>(bytes / kSampleBytesEstimate, twin::kMaxCalibrationSamples);
      }
    }
  } catch (const std::exception&) {
    // No estimate beyond this run's own record.
  }
  return kMargin * kUnitTwinPerSampleS * static_cast<double>(samples);
}

double estimate_report(const RunContext& c) {
  if (!c.request.report) return 0;
  return kMargin * (kReportS + kReportPerSampleS * static_cast<double>(c.samples));
}

// The run's end goes into the index only once every file of its results is on disk (issue
// #22): results.json and status.json as they will stand, the report, results.json final, then
// the index row. The unit twin comes after it: it calibrates over the unit's complete runs in
// the index, and it is the unit's file, not this run's results.
constexpr std::array kStages{
    PostRunStage{"twin", estimate_twin, finish_twin},
    PostRunStage{"twin calibration", estimate_calibration, calibrate_twin},
    PostRunStage{"verdict", estimate_verdict, decide_verdict},
    PostRunStage{"results", estimate_results, write_results},
    PostRunStage{"report", estimate_report, write_report},
    PostRunStage{"record", estimate_results, record_end},
    PostRunStage{"unit twin", estimate_unit_twin, update_unit_twin},
};

// results.json where it can still be written; false with the reason in results otherwise.
bool write_results_file(RunContext& c) {
  try {
    c.store->write_results(c.outcome.run_id, c.results);
    return true;
  } catch (const std::exception& e) {
    c.results["results_error"] = std::string("results.json not written: ") + e.what();
    return false;
  }
}

// A file of the run's results could not be written (the text names the path and the error):
// the run ends aborted for it, its verdict withdrawn, and a report written while it was
// complete removed (it would say PASS for a run that is not).
void abort_for_unwritten(RunContext& c, const std::string& what) {
  if (c.complete()) {
    if (const auto r = c.results.find("report"); r != c.results.end() && r->is_string()) {
      std::error_code ignored;
      std::filesystem::remove(r->get<std::string>(), ignored);
      c.results.erase("report");
    }
  }
  c.abort_with(what);
  c.pass.reset();
  c.decision.reset();
  c.results["status"] = storage::run_status_name(c.outcome.status);
  c.results["reason"] = c.outcome.reason;
  c.results["pass"] = nullptr;
  c.results["verdict"] = nullptr;
  c.results.erase("limit_checks");
  c.results.erase("undecided_counts_as");
}

// An aborted run's results.json, where a new one cannot be made beside it: the one there
// (`processing`, or `complete` from before a later file failed) overwritten in place, so that
// it does not go on saying otherwise than the index.
void land_aborted_results(RunContext& c) {
  if (write_results_file(c)) return;
  try {
    storage::overwrite_file_in_place(c.paths.results, c.results.dump(2) + "\n");
  } catch (const std::exception&) {  // NOLINT(bugprone-empty-catch)
    // None there, or none writable: the index and status.json still say aborted.
  }
}

}  // namespace

std::span<const PostRunStage> post_run_stages() {
  return kStages;
}

void mark_processing(RunContext& c) {
  auto interim = c.results;
  interim["status"] = "processing";
  if (!c.complete()) interim["reason"] = c.outcome.reason;
  try {
    c.store->write_results(c.outcome.run_id, interim);
  } catch (const std::exception&) {
    // The final write reports it; the index row says `running` meanwhile.
  }
}

void finish_twin(RunContext& c) {
  if (!c.twin_beside) return;
  try {
    const auto& live = c.twin_beside->finish();
    c.twin_json = twin::to_json(live);
    c.twin_json["gear"] = c.twin_source;
    // twin.csv is one of the run's files: not on disk, the run is not complete.
    if (!live.overlay_error.empty()) abort_for_unwritten(c, live.overlay_error);
    if (!live.residual) {
      throw std::runtime_error("twin residual: " + std::to_string(live.points) +
                               " points, fewer than 8 with a measured and a predicted TE");
    }
  } catch (const std::exception& e) {
    c.twin_json["error"] = e.what();
  }
}

void calibrate_twin(RunContext& c) {
  if (!calibrates(c) || c.twin_json.contains("error")) return;
  try {
    // The fit's rows are in memory: a long run is calibrated over its first samples.
    const auto samples =
        storage::read_sample_log_page(c.paths.samples, 0, twin::kMaxCalibrationSamples).samples;
    twin::TwinCalibrationOptions options;
    options.solver = c.twin_solver;
    const auto& s = c.procedure_result.static_result;
    c.calibration =
        twin::calibrate_twin(c.twin_gear, c.description.sense, samples, s ? &*s : nullptr, options);
    try {
      twin::write_calibrated_twin_config(c.paths.dir / "twin-calibrated.yaml", *c.calibration);
      // The calibrated twin's replay, for the run page's before/after plot.
      twin::write_replay_csv(c.paths.dir / "twin-calibrated.csv", c.calibration->calibrated,
                             c.description.sense, samples, c.calibration->solver);
    } catch (const std::exception& e) {
      abort_for_unwritten(c, std::string("twin calibration not written: ") + e.what());
      throw;
    }
    c.twin_json["calibration"] = twin::to_json(*c.calibration);
    c.twin_json["calibration"]["config"] = "twin-calibrated.yaml";
  } catch (const std::exception& e) {
    c.twin_json["error"] = e.what();
  }
}

// A run that did not complete keeps the figures of every part its procedure had finished,
// marked as from an aborted run (results.json `partial`).
void keep_finished_figures(RunContext& c) {
  if (c.complete() || !c.procedure_result.json.empty() || !c.finished || c.finished->finished < 1) {
    return;
  }
  try {
    const auto sections = c.finished->sections();
    for (const auto& [key, value] : sections.items()) c.results[key] = value;
    c.results["partial"] = {{"from_aborted_run", true},
                            {"finished", c.finished->finished},
                            {"planned", c.finished->planned},
                            {"unit", c.finished->unit}};
  } catch (const std::exception& e) {
    c.results["warnings"].push_back(std::string("figures finished before the abort not kept: ") +
                                    e.what());
  }
}

void decide_verdict(RunContext& c) {
  auto& results = c.results;
  for (auto& [key, value] : c.procedure_result.json.items()) results[key] = value;
  keep_finished_figures(c);
  if (!c.twin_json.is_null()) results["twin"] = c.twin_json;
  results["status"] = storage::run_status_name(c.outcome.status);
  if (!c.complete()) results["reason"] = c.outcome.reason;
  if (c.complete()) {
    const auto undecided = c.request.spec ? c.request.spec->undecided : UndecidedCounts::kFail;
    auto verdict = check_limits(c.parsed.limits, results, undecided);
    c.pass = verdict.pass;
    c.decision = verdict.decision;
    results["limit_checks"] = verdict.checks;
    results["pass"] = c.pass ? nlohmann::json(*c.pass) : nlohmann::json();
    results["undecided_counts_as"] = undecided_counts_name(undecided);
  }
  results["verdict"] =
      c.decision ? nlohmann::json(metrology::decision_name(*c.decision)) : nlohmann::json();
}

// results.json, and status.json as the index will record the run (the report reads both).
// Not complete, not PASS, when either cannot be written: finished aborted with the error.
void write_results(RunContext& c) {
  if (!write_results_file(c)) {
    abort_for_unwritten(c, c.results["results_error"].get<std::string>());
    return;
  }
  try {
    c.store->write_finished_status(c.outcome.run_id, c.outcome.status, c.outcome.reason, c.pass,
                                   c.decision ? metrology::decision_name(*c.decision) : "");
  } catch (const std::exception& e) {
    abort_for_unwritten(c, std::string("status.json not written: ") + e.what());
  }
}

void write_report(RunContext& c) {
  if (!c.request.report || c.results.contains("results_error")) return;
  try {
    const auto report = report::write_run_report(c.paths.dir);
    c.results["report"] = report.html.string();
  } catch (const std::exception& e) {
    c.results["report_error"] = e.what();
    // Asked for and not on disk: the run's results are not all there.
    abort_for_unwritten(c, std::string("report not written: ") + e.what());
  }
}

// results.json final (the report's path, the post-run timing), then the index row: the run's
// end is recorded once its files are on disk, or as aborted with the reason they are not.
void record_end(RunContext& c) {
  if (c.complete() && !write_results_file(c)) {
    abort_for_unwritten(c, c.results["results_error"].get<std::string>());
  }
  if (!c.complete()) land_aborted_results(c);
  try {
    const auto status_error =
        c.store->finish_run(c.outcome.run_id, c.outcome.status, c.outcome.reason, c.pass,
                            c.decision ? metrology::decision_name(*c.decision) : "");
    if (!status_error.empty()) {
      c.results["status_error"] = "status.json not rewritten: " + status_error;
      c.results["warnings"].push_back(c.results["status_error"]);  // the daemon logs these
    }
  } catch (const std::exception& e) {
    // The index cannot be written (e.g. its disk is full too): the row stays `running` and the
    // next start of a store marks it incomplete; the caller still learns the status here.
    c.results["index_error"] = std::string("run index not updated: ") + e.what();
    c.results["warnings"].push_back(c.results["index_error"]);
  }
}

// The unit's twin anew, over this run and the unit's newest run of every other procedure:
// the twin beside the bench on the unit's next run. After the index row (it reads the unit's
// complete runs there); its outcome joins results.json where that can still be rewritten.
void update_unit_twin(RunContext& c) {
  if (!calibrates(c) || c.unit_serial.empty() || c.results.contains("index_error")) return;
  try {
    const twin::CalibratedRun this_run{c.outcome.run_id, c.request.procedure,
                                       c.calibration ? &*c.calibration : nullptr};
    const auto update = twin::update_unit_twin(*c.store, c.unit_serial, c.description.twin_gear,
                                               c.description.sense, c.description.name, this_run);
    if (update) {
      auto unit_json = update->provenance;
      unit_json.erase("te_terms");
      unit_json["case"] = std::filesystem::relative(update->case_file, c.store->root()).string();
      c.results["twin"]["unit_twin"] = unit_json;
    }
  } catch (const std::exception& e) {
    c.results["twin"]["unit_twin"] = {{"error", e.what()}};
  }
  try {
    c.store->write_results(c.outcome.run_id, c.results);
  } catch (const std::exception& e) {
    c.results["twin"]["unit_twin"]["results_error"] =
        std::string("results.json not rewritten with the unit twin: ") + e.what();
  }
}

}  // namespace wavebench::procedures
