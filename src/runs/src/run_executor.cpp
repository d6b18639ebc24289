#include "wavebench/runs/run_executor.hpp"

#include <atomic>
#include <optional>
#include <stdexcept>
#include <variant>

#include "wavebench/procedures/gear_sense.hpp"
#include "wavebench/runs/dynamic_te_procedure.hpp"
#include "wavebench/runs/lost_motion_procedure.hpp"
#include "wavebench/runs/run_limits.hpp"
#include "wavebench/runs/run_request_check.hpp"
#include "wavebench/runs/sample_recorder.hpp"
#include "wavebench/runs/software_version.hpp"
#include "wavebench/runs/static_te_procedure.hpp"
#include "wavebench/storage/sample_log.hpp"

#if defined(WAVEBENCH_TWIN_AVAILABLE) && __has_include("wavebench/twin/twin_overlay.hpp")
#define WAVEBENCH_RUN_TWIN 1
#include "wavebench/analysis/amplitude_spectrum.hpp"
#include "wavebench/twin/twin_beside_bench.hpp"
#include "wavebench/twin/twin_calibrator.hpp"
#include "wavebench/twin/twin_overlay.hpp"
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

// Keys of a request's options that belong to the run, not to the procedure.
constexpr const char* kLimitsKey = "limits";
constexpr const char* kCalibrateKey = "calibrate_twin";

using AnyProcedure = std::variant<StaticTeProcedure, DynamicTeProcedure, LostMotionProcedure>;

struct ParsedRequest {
  AnyProcedure procedure;
  nlohmann::json procedure_options;
  nlohmann::json limits = nlohmann::json::object();
  bool calibrate_twin = true;
};

ParsedRequest parse_request(const RunRequest& request) {
  if (!request.options.is_object()) {
    throw std::invalid_argument("options: got '" + request.options.dump() +
                                "', expected an object of option keys");
  }
  nlohmann::json options = request.options;
  nlohmann::json limits = nlohmann::json::object();
  if (options.contains(kLimitsKey)) {
    limits = options[kLimitsKey];
    validate_limits(limits);
    options.erase(kLimitsKey);
  }
  bool calibrate = true;
  if (options.contains(kCalibrateKey)) {
    if (!options[kCalibrateKey].is_boolean()) {
      throw std::invalid_argument(std::string(kCalibrateKey) + ": got '" +
                                  options[kCalibrateKey].dump() + "', expected true or false");
    }
    calibrate = options[kCalibrateKey].get<bool>();
    options.erase(kCalibrateKey);
  }
  if (request.procedure == "static") {
    const auto o = StaticTeOptions::from_json(options);
    return {StaticTeProcedure(o), o.to_json(), limits, calibrate};
  }
  if (request.procedure == "dynamic") {
    const auto o = DynamicTeOptions::from_json(options);
    return {DynamicTeProcedure(o), o.to_json(), limits, calibrate};
  }
  if (request.procedure == "lost-motion") {
    const auto o = LostMotionOptions::from_json(options);
    return {LostMotionProcedure(o), o.to_json(), limits, calibrate};
  }
  throw std::invalid_argument("procedure: got '" + request.procedure +
                              "', expected static, dynamic or lost-motion");
}

// Every sample to samples.wbs as it is acquired. A write failure must not take acquisition
// down: it is counted and reported with the run.
class SampleLogObserver final : public bench::SampleObserver {
 public:
  explicit SampleLogObserver(storage::SampleLogWriter& writer) : writer_(writer) {}
  void on_sample(const storage::SyncSample& sample) noexcept override {
    try {
      writer_.append(sample);
      writer_.flush_if_due();
    } catch (const std::exception& e) {
      if (errors_++ == 0) first_error_ = e.what();
    }
  }
  std::uint64_t errors() const { return errors_; }
  const std::string& first_error() const { return first_error_; }

 private:
  storage::SampleLogWriter& writer_;
  std::uint64_t errors_ = 0;
  std::string first_error_;
};

struct ProcedureResult {
  nlohmann::json json = nlohmann::json::object();
  std::optional<procedures::StaticTeResult> static_result;
};

ProcedureResult run_procedure(AnyProcedure& procedure, bench::Bench& bench,
                              const ProcedureProgress& progress) {
  ProcedureResult r;
  if (auto* p = std::get_if<StaticTeProcedure>(&procedure)) {
    auto out = p->run(bench, progress);
    r.json = out.to_json();
    r.static_result = std::move(out.result);
  } else if (auto* d = std::get_if<DynamicTeProcedure>(&procedure)) {
    r.json["dynamic"] = d->run(bench, progress).to_json();
  } else if (auto* l = std::get_if<LostMotionProcedure>(&procedure)) {
    r.json["lost_motion_fit"] = l->run(bench, progress).to_json();
  }
  return r;
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
  return {{"samples_logged", writer.records_appended()},
          {"log_write_errors", log.errors()},
          {"log_first_error", log.first_error()},
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

}  // namespace

void check_run_request(const RunRequest& request) {
  parse_request(request);
}

RunOutcome execute_run(bench::Bench& bench, storage::RunStore& store, const RunRequest& request,
                       const ProgressSink& progress) {
  ParsedRequest parsed = parse_request(request);  // nothing on disk before this passes
  const auto& description = bench.description();

  RunOutcome outcome;
  outcome.run_id = store.create_run(request.procedure, description.unit_serial, request.config_text,
                                    parsed.limits.dump());
  const auto paths = store.paths(outcome.run_id);
  outcome.dir = paths.dir;
  const auto report_progress = [&](const std::string& phase, double fraction) {
    if (progress) progress({outcome.run_id, phase, fraction});
  };

  nlohmann::json results = {
      {"run_id", outcome.run_id},
      {"procedure", request.procedure},
      {"unit_serial", description.unit_serial},
      {"bench", description.name},
      {"software_version", software_version()},
      {"gear",
       {{"ratio", description.sense.ratio}, {"direction_sign", description.sense.direction_sign}}},
      {"sync_period_s", description.sync_period_s},
      {"simulated_clock", description.simulated_clock},
      {"options", parsed.procedure_options},
      {"limits", parsed.limits}};
  ProcedureResult procedure_result;
  nlohmann::json twin_json;
  {
    storage::SampleLogWriter writer(paths.samples);
    SampleLogObserver log(writer);
#if WAVEBENCH_RUN_TWIN
    std::unique_ptr<twin::TwinBesideBench> twin_beside;
    if (request.twin) {
      try {
        twin_beside =
            std::make_unique<twin::TwinBesideBench>(description.twin_gear, description.sense);
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
            parsed.procedure, bench,
            [&](const std::string& phase, double f) { report_progress(phase, 0.9 * f); });
      } catch (const bench::BenchAborted& e) {
        outcome.status = storage::RunStatus::kAborted;
        outcome.reason = e.what();
      } catch (const std::exception& e) {
        make_safe(bench);
        outcome.status = storage::RunStatus::kAborted;
        outcome.reason = std::string("procedure failed: ") + e.what();
      }
    }
    writer.close();
    results["acquisition"] = acquisition_json(bench.acquisition_stats(), writer, log);
#if WAVEBENCH_RUN_TWIN
    if (twin_beside) {
      report_progress("twin", 0.92);
      try {
        const auto& live = twin_beside->finish();
        twin_json = twin::to_json(live);
        twin::write_twin_csv(paths.dir / "twin.csv", live.points);
        analysis::SpectrumAnalyser analyser;
        if (!twin_json.contains("residual")) {
          twin_json["residual"] = procedures::to_json(
              twin::twin_overlay_residual(twin::twin_overlay(live.points), analyser));
        }
        if (parsed.calibrate_twin && outcome.status == storage::RunStatus::kComplete) {
          report_progress("twin calibration", 0.94);
          const auto samples = storage::read_sample_log(paths.samples).samples;
          const auto cal = twin::calibrate_twin(
              description.twin_gear, description.sense, samples, analyser,
              procedure_result.static_result ? &*procedure_result.static_result : nullptr);
          twin::write_calibrated_twin_config(paths.dir / "twin-calibrated.yaml", cal);
          twin_json["calibration"] = twin::to_json(cal);
          twin_json["calibration"]["config"] = "twin-calibrated.yaml";
        }
      } catch (const std::exception& e) {
        twin_json["error"] = e.what();
      }
    }
#endif
  }

  for (auto& [key, value] : procedure_result.json.items()) results[key] = value;
  if (!twin_json.is_null()) results["twin"] = twin_json;
  results["status"] = storage::run_status_name(outcome.status);
  if (outcome.status != storage::RunStatus::kComplete) results["reason"] = outcome.reason;
  std::optional<bool> pass;
  if (outcome.status == storage::RunStatus::kComplete) {
    auto verdict = check_limits(parsed.limits, results);
    pass = verdict.pass;
    results["limit_checks"] = verdict.checks;
    results["pass"] = pass ? nlohmann::json(*pass) : nlohmann::json();
  }
  store.write_results(outcome.run_id, results);
  store.finish_run(outcome.run_id, outcome.status, outcome.reason, pass);

#if WAVEBENCH_RUN_REPORT
  if (request.report) {
    report_progress("report", 0.97);
    try {
      const auto report = report::write_run_report(paths.dir);
      results["report"] = report.html.string();
    } catch (const std::exception& e) {
      results["report_error"] = e.what();
    }
    store.write_results(outcome.run_id, results);
  }
#endif
  outcome.results = std::move(results);
  report_progress("done", 1.0);
  return outcome;
}

}  // namespace wavebench::runs
