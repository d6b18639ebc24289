#include "wavebench/procedures/run_executor.hpp"

#include <chrono>

#include "beside_idling_bench.hpp"
#include "post_run_stages.hpp"
#include "run_context.hpp"
#include "wavebench/procedures/recorded_run.hpp"

namespace wavebench::procedures {

RecordedRun::RecordedRun(std::unique_ptr<RunContext> context) : context_(std::move(context)) {}
RecordedRun::~RecordedRun() = default;
RecordedRun::RecordedRun(RecordedRun&&) noexcept = default;
RecordedRun& RecordedRun::operator=(RecordedRun&&) noexcept = default;

const std::string& RecordedRun::run_id() const {
  return context_->outcome.run_id;
}
const std::string& RecordedRun::procedure() const {
  return context_->request.procedure;
}
const std::string& RecordedRun::unit_serial() const {
  return context_->unit_serial;
}

double RecordedRun::post_run_estimate_s() const {
  double total = 0;
  for (const auto& stage : post_run_stages()) total += stage.estimate_s(*context_);
  return total;
}

RunOutcome RecordedRun::finish(const ProgressSink& progress) {
  RunContext& c = *context_;
  const auto stages = post_run_stages();
  std::vector<double> estimates;
  double total = 0;
  for (const auto& stage : stages) total += estimates.emplace_back(stage.estimate_s(c));
  double done = 0;
  // How long each stage took against its estimate (what the constants are measured from), in
  // the results as it goes: the stage that writes them final carries the stages before it.
  c.results["timing"]["post_run"] = nlohmann::json::object();
  c.results["timing"]["samples"] = c.samples;
  for (std::size_t i = 0; i < stages.size(); ++i) {
    if (progress) {
      progress({c.outcome.run_id, stages[i].phase, total > 0 ? done / total : 0, total - done});
    }
    const auto start = std::chrono::steady_clock::now();
    stages[i].run(c);
    const double spent =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    c.results["timing"]["post_run"][stages[i].phase] = {{"estimated_s", estimates[i]},
                                                        {"spent_s", spent}};
    done += estimates[i];
  }
  if (!c.results.contains("results_error") && !c.results.contains("index_error")) {
    try {
      c.store->write_results(c.outcome.run_id, c.results);
    } catch (const std::exception&) {
      // The run's results are on disk already, without the timing.
    }
  }
  c.request.on_diagnosis = nullptr;
  c.outcome.results = c.results;
  if (progress) progress({c.outcome.run_id, "done", 1.0, 0.0});
  return c.outcome;
}

RunOutcome execute_run(bench::Bench& bench, storage::RunStore& store, const RunRequest& request,
                       const ProgressSink& progress) {
  auto recorded = record_run(bench, store, request, [&](const RunProgress& p) {
    if (progress) progress({p.run_id, p.phase, 0.9 * p.fraction, -1});
  });
  // Everything after the recording works on disk and CPU only: beside the bench, so that its
  // event loop keeps turning (heartbeats, SYNC, the live view) meanwhile.
  RunOutcome outcome;
  run_beside_idling_bench(bench, [&] {
    outcome = recorded.finish([&](const RunProgress& p) {
      if (progress) progress({p.run_id, p.phase, 0.9 + 0.1 * p.fraction, -1});
    });
  });
  return outcome;
}

}  // namespace wavebench::procedures
