#include "wavebench/runs/run_executor.hpp"

#include <atomic>
#include <optional>
#include <stdexcept>
#include <type_traits>
#include <variant>

#include "beside_idling_bench.hpp"
#include "parsed_request.hpp"
#include "repeat_combination.hpp"
#include "run_request_check_detail.hpp"
#include "wavebench/procedures/gear_sense.hpp"
#include "wavebench/runs/run_limits.hpp"
#include "wavebench/runs/sample_log_observer.hpp"
#include "wavebench/runs/sample_recorder.hpp"
#include "wavebench/runs/software_version.hpp"
#include "wavebench/storage/sample_log.hpp"

#if defined(WAVEBENCH_TWIN_AVAILABLE) && __has_include("wavebench/twin/twin_overlay.hpp")
#define WAVEBENCH_RUN_TWIN 1
#include "wavebench/analysis/amplitude_spectrum.hpp"
#include "wavebench/twin/twin_beside_bench.hpp"
#include "wavebench/twin/twin_calibrator.hpp"
#include "wavebench/twin/twin_overlay.hpp"
#include "wavebench/twin/unit_twin_store.hpp"
#else
#define WAVEBENCH_RUN_TWIN 0
#endif
#if defined(WAVEBENCH_REPORT_AVAILABLE) && __has_include("wavebench/report/run_report.hpp")
#define WAVEBENCH_RUN_REPORT 1
#include "wavebench/report/run_report.hpp"
#else
#define WAVEBENCH_RUN_REPORT 0
#endif

namespace wavebench::runs {

namespace {

struct ProcedureResult {
  nlohmann::json json = nlohmann::json::object();
  std::optional<procedures::StaticTeResult> static_result;
};

// Each procedure names its results.json section (kResultsSection); a new alternative of
// AnyProcedure that does not fails to compile here rather than running with no results.
ProcedureResult run_once(AnyProcedure& procedure, bench::Bench& bench,
                         const ProcedureProgress& progress) {
  return std::visit(
      [&](auto& p) {
        using Procedure = std::decay_t<decltype(p)>;
        ProcedureResult r;
        auto out = p.run(bench, progress);
        if constexpr (Procedure::kResultsSection.empty()) {
          r.json = out.to_json();
        } else {
          r.json[std::string(Procedure::kResultsSection)] = out.to_json();
        }
        if constexpr (std::is_same_v<Procedure, StaticTeProcedure>) {
          r.static_result = std::move(out.result);  // the twin calibration takes it
        }
        return r;
      },
      procedure);
}

// The procedure `repeats` times, generically (any alternative of AnyProcedure): each repeat's
// sections in `repeats`, the run's sections their combination (repeat_combination.hpp). The
// twin calibration takes the first repeat's static result.
ProcedureResult run_procedure(AnyProcedure& procedure, bench::Bench& bench, int repeats,
                              const ProcedureProgress& progress) {
  if (repeats <= 1) return run_once(procedure, bench, progress);
  ProcedureResult first;
  std::vector<nlohmann::json> sections;
  for (int i = 0; i < repeats; ++i) {
    const std::string label = "repeat " + std::to_string(i + 1) + "/" + std::to_string(repeats);
    auto r = run_once(procedure, bench, [&](const std::string& phase, double f) {
      if (progress) progress(label + ": " + phase, (i + f) / repeats);
    });
    sections.push_back(std::move(r.json));
    if (i == 0) first.static_result = std::move(r.static_result);
  }
  first.json = combine_repeats(sections);
  first.json["repeats"] = std::move(sections);
  return first;
}

// After a failure that is not a trip (e.g. a move that never reached its target): brake
// released and motion stopped where the bench still allows it.
void make_safe(bench::Bench& bench) noexcept {
  try {
    bench.stop_motion();
  } catch (...) {
  }
  try {
    bench.set_brake_torque(0);
  } catch (...) {
  }
}

nlohmann::json acquisition_json(const bench::AcquisitionStats& a,
                                const storage::SampleLogWriter& writer,
                                const SampleLogObserver& log) {
  const auto& g = writer.gap_totals();
  return {{"samples_logged", writer.records_flushed()},
          {"log_write_errors", log.samples_not_logged()},
          {"log_queue_dropped", log.samples_dropped()},
          {"log_first_error", log.failure()},
          {"missed_syncs", g.missed_cycles},
          {"incomplete_samples", g.incomplete_samples},
          {"gaps", g.gaps},
          {"counter_anomalies", g.anomalies},
          {"bench_syncs_sent", a.syncs_sent},
          {"bench_samples", a.samples},
          {"bench_incomplete_samples", a.incomplete_samples},
          {"bench_sync_late", a.sync_late},
          {"bench_sync_skipped", a.sync_skipped},
          {"bench_bus_load", a.bus_load}};
}

// results.json where it can still be written: a full disk must not turn an aborted run into
// an exception (the index row and the outcome carry the status and reason either way).
void write_results_if_possible(storage::RunStore& store, const std::string& id,
                               nlohmann::json& results) {
  try {
    store.write_results(id, results);
  } catch (const std::exception& e) {
    results["results_error"] = std::string("results.json not written: ") + e.what();
  }
}

// results.json "spec": what the verdict was judged against.
// The bench's measuring devices with the calibration its config states (null: not stated).
nlohmann::json sensors_json(const std::vector<bench::SensorCalibration>& sensors) {
  nlohmann::json out = nlohmann::json::array();
  for (const auto& s : sensors) {
    out.push_back({{"sensor", s.sensor},
                   {"calibration_id", s.id.empty() ? nlohmann::json() : nlohmann::json(s.id)},
                   {"calibration_due", s.due.empty() ? nlohmann::json() : nlohmann::json(s.due)}});
  }
  return out;
}

nlohmann::json spec_json(const ProductSpec& spec) {
  const auto j = spec.to_json();
  return {{"name", j["name"]},
          {"model", j["model"]},
          {"description", j["description"]},
          {"lost_motion_at_percent", j["lost_motion_at_percent"]},
          {"undecided", j["undecided"]},
          {"limits", j["limits"]}};
}

}  // namespace

RunOutcome execute_run(bench::Bench& bench, storage::RunStore& store, const RunRequest& request,
                       const ProgressSink& progress) {
  const auto& description = bench.description();
  // Nothing on disk and nothing moved before the whole request passes.
  ParsedRequest parsed = check_and_parse(request, description, bench.extra_channels().size(),
                                         run_budget(store.root()));

  RunOutcome outcome;
  const std::string unit_serial =
      request.unit_serial.empty() ? description.unit_serial : request.unit_serial;
  outcome.run_id = store.create_run(request.procedure, unit_serial, request.config_text,
                                    parsed.limits.dump(), request.spec ? request.spec->name : "");
  const auto paths = store.paths(outcome.run_id);
  outcome.dir = paths.dir;
  const auto report_progress = [&](const std::string& phase, double fraction) {
    if (progress) progress({outcome.run_id, phase, fraction});
  };
  const auto abort_with = [&](const std::string& reason) {
    if (outcome.status == storage::RunStatus::kAborted) return;  // the first reason stands
    outcome.status = storage::RunStatus::kAborted;
    outcome.reason = reason;
  };

  nlohmann::json results = {
      {"schema", kResultsSchema},
      {"run_id", outcome.run_id},
      {"procedure", request.procedure},
      {"unit_serial", unit_serial},
      {"operator", request.operator_name.empty() ? nlohmann::json(nullptr)
                                                 : nlohmann::json(request.operator_name)},
      {"bench", description.name},
      {"bench_sensors", sensors_json(description.sensors)},
      {"software_version", software_version()},
      {"software_commit", software_commit()},
      {"gear",
       {{"ratio", description.sense.ratio}, {"direction_sign", description.sense.direction_sign}}},
      {"sync_period_s", description.sync_period_s},
      {"simulated_clock", description.simulated_clock},
      {"absent_channels", bench.absent_channels()},
      {"options", parsed.procedure_options},
      {"limits", parsed.limits},
      {"spec", request.spec ? spec_json(*request.spec) : nlohmann::json()}};
  ProcedureResult procedure_result;
  nlohmann::json twin_json;
#if WAVEBENCH_RUN_TWIN
  std::optional<twin::TwinCalibration> cal;  // the twin fitted to this run alone
#endif
  std::optional<storage::SampleLogWriter> writer;
#if WAVEBENCH_RUN_TWIN
  std::unique_ptr<twin::TwinBesideBench> twin_beside;
  // The twin beside the bench: the unit's own when it has one (calibrated over its earlier
  // runs, unit_twin_store.hpp), else the bench's nominal twin case.
  model::GearParams twin_gear = description.twin_gear;
  twin::TwinSolverOptions twin_solver;
  nlohmann::json twin_source = {{"kind", "nominal"}, {"case", description.twin_case_path}};
  if (request.twin && !unit_serial.empty()) {
    try {
      if (auto unit = twin::load_unit_twin(store.root(), unit_serial, description.sense.ratio)) {
        twin_gear = std::move(unit->twin.gear);
        twin_solver = unit->solver;
        nlohmann::json from = nlohmann::json::array();
        for (const auto& r : unit->provenance.value("runs", nlohmann::json::array())) {
          from.push_back(
              {{"run_id", r.value("run_id", "")}, {"procedure", r.value("procedure", "")}});
        }
        twin_source = {{"kind", "unit"},
                       {"case", std::filesystem::relative(unit->case_file, store.root()).string()},
                       {"calibrated_from", from}};
      }
    } catch (const std::exception& e) {
      results["warnings"].push_back(std::string(e.what()) + "; the nominal twin case is used");
    }
  }
#endif
  const auto extra_channels = bench.extra_channels();
  if (!extra_channels.empty()) {
    nlohmann::json channels = nlohmann::json::array();
    for (const auto& c : extra_channels) channels.push_back({{"name", c.name}, {"unit", c.unit}});
    results["extra_channels"] = channels;
  }
  try {
    storage::SampleLogWriterOptions options;
    options.extra_channels = extra_channels;
    writer.emplace(paths.samples, options);
  } catch (const std::exception& e) {
    abort_with(std::string("sample log not created, nothing moved: ") + e.what());
  }
  if (writer) {
    SampleLogObserver log(*writer, bench);
#if WAVEBENCH_RUN_TWIN
    if (request.twin) {
      try {
        twin::TwinBesideBenchOptions twin_options;
        twin_options.diagnosis.sensor_noise_rad = description.output_encoder_noise_rad;
        if (request.on_diagnosis) {
          twin_options.on_flag = [&request](const twin::DiagnosticFlag& flag) {
            request.on_diagnosis(twin::to_json(flag));
          };
        }
        twin_options.solver = twin_solver;
        twin_options.overlay_csv = paths.dir / "twin.csv";
        if (description.simulated_clock) twin_options.lockstep_backlog = 1024;
        twin_beside =
            std::make_unique<twin::TwinBesideBench>(twin_gear, description.sense, twin_options);
      } catch (const std::exception& e) {
        twin_json = {{"error", std::string("twin not started: ") + e.what()}};
      }
    }
#endif
    {
      ObserverRegistration log_registration(bench, log);
#if WAVEBENCH_RUN_TWIN
      std::optional<ObserverRegistration> twin_registration;
      if (twin_beside) twin_registration.emplace(bench, *twin_beside);
#endif
      report_progress(request.procedure + " start", 0);
      try {
        procedure_result = run_procedure(
            parsed.procedure, bench, parsed.repeats,
            [&](const std::string& phase, double f) { report_progress(phase, 0.9 * f); });
      } catch (const bench::BenchAborted& e) {
        // A trip the log asked for is reported as the log's failure, not as an operator stop.
        abort_with(log.failed() ? log.failure() : std::string(e.what()));
      } catch (const std::exception& e) {
        make_safe(bench);
        abort_with(log.failed() ? log.failure() : std::string("procedure failed: ") + e.what());
      }
    }
    // Every queued sample to the file before the run is finalised. The log may fail after the
    // procedure's last blocking call, or while draining: the run is still missing samples.
    log.finish();
    if (log.failed()) abort_with(log.failure());
    // The servo is powered only while the run needs it: complete, aborted or failed, the
    // drive goes off and the brake output too. The power-down is not part of the record: its
    // samples entered the twin's calibration, which fits the whole log (dynamic runs on the
    // simulated bench: residual 0.81-1.07 arcsec with them, 0.62-0.77 without).
    bench.deactivate();
    try {
      writer->close();
    } catch (const std::exception& e) {
      abort_with(std::string("sample log: not closed cleanly: ") + e.what());
    }
    results["acquisition"] = acquisition_json(bench.acquisition_stats(), *writer, log);
    if (log.samples_dropped() > 0) {
      results["warnings"].push_back("sample log: " + std::to_string(log.samples_dropped()) +
                                    " samples dropped, its queue was full (the disk fell behind)");
    }
  }

  // Everything after the procedure works on disk and CPU only: beside the bench, so that its
  // event loop keeps turning (heartbeats, SYNC, the live view) meanwhile.
  run_beside_idling_bench(bench, [&] {
#if WAVEBENCH_RUN_TWIN
    if (twin_beside) {
      report_progress("twin", 0.92);
      try {
        const auto& live = twin_beside->finish();
        twin_json = twin::to_json(live);
        twin_json["gear"] = twin_source;
        if (!live.residual) {
          throw std::runtime_error("twin residual: " + std::to_string(live.points) +
                                   " points, fewer than 8 with a measured and a predicted TE");
        }
        if (parsed.calibrate_twin && outcome.status == storage::RunStatus::kComplete) {
          report_progress("twin calibration", 0.94);
          // The fit's rows are in memory: a long run is calibrated over its first samples.
          const auto samples =
              storage::read_sample_log_page(paths.samples, 0, twin::kMaxCalibrationSamples).samples;
          twin::TwinCalibrationOptions calibration_options;
          calibration_options.solver = twin_solver;
          cal = twin::calibrate_twin(
              twin_gear, description.sense, samples,
              procedure_result.static_result ? &*procedure_result.static_result : nullptr,
              calibration_options);
          twin::write_calibrated_twin_config(paths.dir / "twin-calibrated.yaml", *cal);
          // The calibrated twin's replay, for the run page's before/after plot.
          twin::write_replay_csv(paths.dir / "twin-calibrated.csv", cal->calibrated,
                                 description.sense, samples, cal->solver);
          twin_json["calibration"] = twin::to_json(*cal);
          twin_json["calibration"]["config"] = "twin-calibrated.yaml";
        }
      } catch (const std::exception& e) {
        twin_json["error"] = e.what();
      }
    }
#endif

    for (auto& [key, value] : procedure_result.json.items()) results[key] = value;
    if (!twin_json.is_null()) results["twin"] = twin_json;
    results["status"] = storage::run_status_name(outcome.status);
    if (outcome.status != storage::RunStatus::kComplete) results["reason"] = outcome.reason;
    std::optional<bool> pass;
    std::optional<procedures::LimitDecision> decision;
    if (outcome.status == storage::RunStatus::kComplete) {
      const auto undecided = request.spec ? request.spec->undecided : UndecidedCounts::kFail;
      auto verdict = check_limits(parsed.limits, results, undecided);
      pass = verdict.pass;
      decision = verdict.decision;
      results["limit_checks"] = verdict.checks;
      results["pass"] = pass ? nlohmann::json(*pass) : nlohmann::json();
      results["undecided_counts_as"] = undecided_counts_name(undecided);
    }
    results["verdict"] =
        decision ? nlohmann::json(procedures::decision_name(*decision)) : nlohmann::json();
    write_results_if_possible(store, outcome.run_id, results);
    try {
      store.finish_run(outcome.run_id, outcome.status, outcome.reason, pass,
                       decision ? procedures::decision_name(*decision) : "");
    } catch (const std::exception& e) {
      // The index cannot be written (e.g. its disk is full too): the row stays `running` and the
      // next start of a store marks it incomplete; the caller still learns the status here.
      results["index_error"] = std::string("run index not updated: ") + e.what();
    }

#if WAVEBENCH_RUN_TWIN
    // The unit's twin anew, over this run and the unit's newest run of every other procedure:
    // the twin beside the bench on the unit's next run.
    if (twin_beside && parsed.calibrate_twin && !unit_serial.empty() &&
        outcome.status == storage::RunStatus::kComplete && !results.contains("index_error")) {
      report_progress("unit twin", 0.95);
      try {
        const twin::CalibratedRun this_run{outcome.run_id, request.procedure,
                                           cal ? &*cal : nullptr};
        const auto update = twin::update_unit_twin(store, unit_serial, description.twin_gear,
                                                   description.sense, description.name, this_run);
        if (update) {
          auto unit_json = update->provenance;
          unit_json.erase("te_terms");
          unit_json["case"] = std::filesystem::relative(update->case_file, store.root()).string();
          results["twin"]["unit_twin"] = unit_json;
        }
      } catch (const std::exception& e) {
        results["twin"]["unit_twin"] = {{"error", e.what()}};
      }
      write_results_if_possible(store, outcome.run_id, results);
    }
#endif

#if WAVEBENCH_RUN_REPORT
    if (request.report && !results.contains("results_error")) {
      report_progress("report", 0.97);
      try {
        const auto report = report::write_run_report(paths.dir);
        results["report"] = report.html.string();
      } catch (const std::exception& e) {
        results["report_error"] = e.what();
      }
      write_results_if_possible(store, outcome.run_id, results);
    }
#endif
  });
  outcome.results = std::move(results);
  report_progress("done", 1.0);
  return outcome;
}

}  // namespace wavebench::runs
