// The recording part of a run (recorded_run.hpp): on the bench thread, from the request's
// check to the bench deactivated and the samples log closed.
#include <chrono>
#include <stdexcept>
#include <type_traits>
#include <variant>

#include "post_run_stages.hpp"
#include "recording_clock.hpp"
#include "repeat_combination.hpp"
#include "run_context.hpp"
#include "run_request_check_detail.hpp"
#include "wavebench/runs/recorded_run.hpp"
#include "wavebench/runs/run_limits.hpp"
#include "wavebench/runs/sample_log_observer.hpp"
#include "wavebench/runs/sample_recorder.hpp"
#include "wavebench/runs/software_version.hpp"
#include "wavebench/storage/sample_log.hpp"
#include "wavebench/twin/twin_overlay.hpp"
#include "wavebench/twin/unit_twin_store.hpp"

namespace wavebench::runs {

namespace {

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

// results.json "spec": what the verdict was judged against.
nlohmann::json spec_json(const ProductSpec& spec) {
  const auto j = spec.to_json();
  return {{"name", j["name"]},
          {"model", j["model"]},
          {"description", j["description"]},
          {"lost_motion_at_percent", j["lost_motion_at_percent"]},
          {"undecided", j["undecided"]},
          {"limits", j["limits"]}};
}

nlohmann::json results_head(const RunContext& c, const bench::Bench& bench) {
  const auto& d = c.description;
  const auto& r = c.request;
  return {{"schema", kResultsSchema},
          {"run_id", c.outcome.run_id},
          {"procedure", r.procedure},
          {"unit_serial", c.unit_serial},
          {"operator",
           r.operator_name.empty() ? nlohmann::json(nullptr) : nlohmann::json(r.operator_name)},
          {"bench", d.name},
          {"bench_sensors", sensors_json(d.sensors)},
          {"software_version", software_version()},
          {"software_commit", software_commit()},
          {"gear", {{"ratio", d.sense.ratio}, {"direction_sign", d.sense.direction_sign}}},
          {"sync_period_s", d.sync_period_s},
          {"simulated_clock", d.simulated_clock},
          {"absent_channels", bench.absent_channels()},
          {"options", c.parsed.procedure_options},
          {"limits", c.parsed.limits},
          {"spec", r.spec ? spec_json(*r.spec) : nlohmann::json()}};
}

// The twin beside the bench: the unit's own when it has one on disk now (calibrated over its
// earlier runs, unit_twin_store.hpp), else the bench's nominal twin case.
void choose_twin(RunContext& c) {
  c.twin_gear = c.description.twin_gear;
  c.twin_source = {{"kind", "nominal"}, {"case", c.description.twin_case_path}};
  if (!c.request.twin || c.unit_serial.empty()) return;
  try {
    auto unit = twin::load_unit_twin(c.store->root(), c.unit_serial, c.description.sense.ratio);
    if (!unit) return;
    c.twin_gear = std::move(unit->twin.gear);
    c.twin_solver = unit->solver;
    nlohmann::json from = nlohmann::json::array();
    for (const auto& r : unit->provenance.value("runs", nlohmann::json::array())) {
      from.push_back({{"run_id", r.value("run_id", "")}, {"procedure", r.value("procedure", "")}});
    }
    c.twin_source = {{"kind", "unit"},
                     {"case", std::filesystem::relative(unit->case_file, c.store->root()).string()},
                     {"calibrated_from", from}};
  } catch (const std::exception& e) {
    c.results["warnings"].push_back(std::string(e.what()) + "; the nominal twin case is used");
  }
}

void start_twin(RunContext& c) {
  if (!c.request.twin) return;
  try {
    twin::TwinBesideBenchOptions options;
    options.diagnosis.sensor_noise_rad = c.description.output_encoder_noise_rad;
    if (c.request.on_diagnosis) {
      // The context outlives the twin's thread (finish() joins it).
      options.on_flag = [&c](const twin::DiagnosticFlag& flag) {
        if (c.request.on_diagnosis) c.request.on_diagnosis(twin::to_json(flag));
      };
    }
    options.solver = c.twin_solver;
    options.overlay_csv = c.paths.dir / "twin.csv";
    if (c.description.simulated_clock) options.lockstep_backlog = 1024;
    c.twin_beside =
        std::make_unique<twin::TwinBesideBench>(c.twin_gear, c.description.sense, options);
  } catch (const std::exception& e) {
    c.twin_json = {{"error", std::string("twin not started: ") + e.what()}};
  }
}

}  // namespace

RecordedRun record_run(bench::Bench& bench, storage::RunStore& store, const RunRequest& request,
                       const ProgressSink& progress) {
  RunEstimate estimate;
  // Nothing on disk and nothing moved before the whole request passes.
  auto context = std::make_unique<RunContext>(check_and_parse(request, bench.description(),
                                                              bench.extra_channels().size(),
                                                              run_budget(store.root()), &estimate));
  RunContext& c = *context;
  c.request = request;
  c.description = bench.description();
  c.store = &store;
  c.unit_serial = request.unit_serial.empty() ? c.description.unit_serial : request.unit_serial;
  c.outcome.run_id =
      store.create_run(request.procedure, c.unit_serial, request.config_text,
                       c.parsed.limits.dump(), request.spec ? request.spec->name : "");
  c.paths = store.paths(c.outcome.run_id);
  c.outcome.dir = c.paths.dir;
  const auto started = std::chrono::steady_clock::now();
  RecordingClock clock(estimate.bench_time_s);
  const auto report_progress = [&](const std::string& phase, double procedure_fraction) {
    if (!progress) return;
    const double elapsed =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    const auto timed = clock.at(procedure_fraction, elapsed);
    progress({c.outcome.run_id, phase, timed.fraction, timed.remaining_s});
  };

  c.results = results_head(c, bench);
  choose_twin(c);
  const auto extra_channels = bench.extra_channels();
  if (!extra_channels.empty()) {
    nlohmann::json channels = nlohmann::json::array();
    for (const auto& ch : extra_channels) {
      channels.push_back({{"name", ch.name}, {"unit", ch.unit}});
    }
    c.results["extra_channels"] = channels;
  }
  std::optional<storage::SampleLogWriter> writer;
  try {
    storage::SampleLogWriterOptions options;
    options.extra_channels = extra_channels;
    writer.emplace(c.paths.samples, options);
  } catch (const std::exception& e) {
    c.abort_with(std::string("sample log not created, nothing moved: ") + e.what());
  }
  if (writer) {
    SampleLogObserver log(*writer, bench);
    start_twin(c);
    {
      ObserverRegistration log_registration(bench, log);
      std::optional<ObserverRegistration> twin_registration;
      if (c.twin_beside) twin_registration.emplace(bench, *c.twin_beside);
      report_progress(request.procedure + " start", 0);
      if (auto* static_te = std::get_if<StaticTeProcedure>(&c.parsed.procedure)) {
        static_te->set_point_sink(request.on_point);
      }
      // Every procedure that measures in parts hands them over as they finish. Not with
      // repeats: the parts of one repeat alone would pass for the run's.
      std::visit(
          [&c](auto& p) {
            if constexpr (requires { p.set_finished_sink(FinishedFiguresSink{}); }) {
              if (c.parsed.repeats > 1) return;
              p.set_finished_sink([&c](FinishedFigures f) { c.finished = std::move(f); });
            }
          },
          c.parsed.procedure);
      try {
        c.procedure_result =
            run_procedure(c.parsed.procedure, bench, c.parsed.repeats, report_progress);
      } catch (const bench::BenchAborted& e) {
        // A trip the log asked for is reported as the log's failure, not as an operator stop.
        c.abort_with(log.failed() ? log.failure() : std::string(e.what()));
      } catch (const std::exception& e) {
        make_safe(bench);
        c.abort_with(log.failed() ? log.failure() : std::string("procedure failed: ") + e.what());
      }
    }
    // Every queued sample to the file before the run is finalised. The log may fail after the
    // procedure's last blocking call, or while draining: the run is still missing samples.
    log.finish();
    if (log.failed()) c.abort_with(log.failure());
    // The servo is powered only while the run needs it: complete, aborted or failed, the
    // drive goes off and the brake output too. The power-down is not part of the record: its
    // samples entered the twin's calibration, which fits the whole log (dynamic runs on the
    // simulated bench: residual 0.81-1.07 arcsec with them, 0.62-0.77 without).
    bench.deactivate();
    try {
      writer->close();
    } catch (const std::exception& e) {
      c.abort_with(std::string("sample log: not closed cleanly: ") + e.what());
    }
    c.samples = writer->records_flushed();
    c.results["acquisition"] = acquisition_json(bench.acquisition_stats(), *writer, log);
    if (log.samples_dropped() > 0) {
      c.results["warnings"].push_back(
          "sample log: " + std::to_string(log.samples_dropped()) +
          " samples dropped, its queue was full (the disk fell behind)");
    }
  }
  c.results["timing"] = {
      {"recording_s",
       std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count()},
      {"recording_planned_s", estimate.bench_time_s}};
  mark_processing(c);
  if (progress) progress({c.outcome.run_id, "recorded", 1.0, 0.0});
  return RecordedRun(std::move(context));
}

}  // namespace wavebench::runs
