// The recording part of a run (recorded_run.hpp): on the bench thread, from the request's
// check to the bench deactivated and the samples log closed.
#include <chrono>
#include <stdexcept>
#include <type_traits>
#include <variant>

#include "post_run_stages.hpp"
#include "recording_clock.hpp"
#include "recording_stages.hpp"
#include "repeat_combination.hpp"
#include "run_context.hpp"
#include "run_request_check_detail.hpp"
#include "wavebench/procedures/recorded_run.hpp"
#include "wavebench/procedures/run_limits.hpp"
#include "wavebench/procedures/sample_log_observer.hpp"
#include "wavebench/procedures/sample_recorder.hpp"
#include "wavebench/procedures/software_version.hpp"
#include "wavebench/storage/sample_log.hpp"
#include "wavebench/twin/twin_overlay.hpp"
#include "wavebench/twin/unit_twin_store.hpp"

namespace wavebench::procedures {

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

  // The recording is the loop over its stages (recording_stages.hpp) around the procedure.
  auto stages = recording_stages();
  for (auto& stage : stages) {
    if (c.complete()) stage->start(c, bench);
  }
  if (c.complete()) {
    {
      std::vector<std::unique_ptr<ObserverRegistration>> registrations;
      for (auto& stage : stages) {
        if (stage->observes())
          registrations.push_back(std::make_unique<ObserverRegistration>(bench, *stage));
      }
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
      // A trip a stage asked for (the sample log's failing disk) is reported as that stage's
      // reason, not as an operator stop.
      const auto stage_trip = [&stages]() -> std::optional<std::string> {
        for (const auto& stage : stages) {
          if (auto reason = stage->trip_reason()) return reason;
        }
        return std::nullopt;
      };
      try {
        c.procedure_result =
            run_procedure(c.parsed.procedure, bench, c.parsed.repeats, report_progress);
      } catch (const bench::BenchAborted& e) {
        c.abort_with(stage_trip().value_or(std::string(e.what())));
      } catch (const std::exception& e) {
        make_safe(bench);
        c.abort_with(stage_trip().value_or(std::string("procedure failed: ") + e.what()));
      }
    }
    for (auto& stage : stages) stage->finish(c);
    // The servo is powered only while the run needs it: complete, aborted or failed, the
    // drive goes off and the brake output too. The power-down is not part of the record: its
    // samples entered the twin's calibration, which fits the whole log (dynamic runs on the
    // simulated bench: residual 0.81-1.07 arcsec with them, 0.62-0.77 without).
    bench.deactivate();
    for (auto& stage : stages) stage->close(c, bench);
  }
  c.results["timing"] = {
      {"recording_s",
       std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count()},
      {"recording_planned_s", estimate.bench_time_s}};
  mark_processing(c);
  if (progress) progress({c.outcome.run_id, "recorded", 1.0, 0.0});
  return RecordedRun(std::move(context));
}

}  // namespace wavebench::procedures
