#pragma once
// A stand-in for procedures::execute_run with the same contract: a bad request throws before
// anything is created; the run's samples go to samples.wbs as acquired; a trip finishes the
// run aborted with the trip's reason. Option "seconds" is the bench time the run takes.

#include <atomic>
#include <stdexcept>

#include "wavebench/daemon/run_launcher.hpp"
#include "wavebench/storage/sample_log.hpp"

namespace wavebench::daemon::testing {

class SampleLogObserver : public bench::SampleObserver {
 public:
  explicit SampleLogObserver(storage::SampleLogWriter& writer) : writer_(writer) {}
  void on_sample(const storage::SyncSample& s) noexcept override {
    writer_.append(s);
    writer_.flush_if_due();
  }

 private:
  storage::SampleLogWriter& writer_;
};

class FakeRunLauncher : public RunLauncher {
 public:
  procedures::RunOutcome launch(bench::Bench& bench, storage::RunStore& store,
                          const procedures::RunRequest& request,
                          const procedures::ProgressSink& progress) override {
    check(request, bench.description(), bench.extra_channels().size(), store.root());
    const double seconds = request.options.value("seconds", 0.2);
    procedures::RunOutcome outcome;
    outcome.run_id =
        store.create_run(request.procedure, bench.description().unit_serial, request.config_text);
    outcome.dir = store.paths(outcome.run_id).dir;
    storage::SampleLogWriterOptions options;
    options.flush_every_records = 10;
    storage::SampleLogWriter writer(store.paths(outcome.run_id).samples, options);
    SampleLogObserver observer(writer);
    bench.add_observer(observer);
    if (progress) progress({outcome.run_id, "fake " + request.procedure, 0});
    try {
      const int steps = 10;
      for (int i = 0; i < steps; ++i) {
        bench.wait_for(seconds / steps);
        if (progress) progress({outcome.run_id, "fake " + request.procedure, (i + 1.0) / steps});
      }
      bench.remove_observer(observer);
      writer.close();
      outcome.results = {{"procedure", request.procedure},
                         {"samples", writer.records_appended()},
                         {"options", request.options},
                         {"operator", request.operator_name}};
      store.write_results(outcome.run_id, outcome.results);
      store.finish_run(outcome.run_id, storage::RunStatus::kComplete, "", true);
      outcome.status = storage::RunStatus::kComplete;
    } catch (const bench::BenchAborted& e) {
      bench.remove_observer(observer);
      writer.close();
      store.finish_run(outcome.run_id, storage::RunStatus::kAborted, e.what());
      outcome.status = storage::RunStatus::kAborted;
      outcome.reason = e.what();
    }
    ++runs_launched;
    return outcome;
  }

  void check(const procedures::RunRequest& request, const bench::BenchDescription& /*bench*/,
             std::size_t /*extra_channels*/,
             const std::filesystem::path& /*runs_root*/) const override {
    if (request.procedure != "static" && request.procedure != "dynamic" &&
        request.procedure != "lost-motion" && request.procedure != "torsional") {
      throw std::invalid_argument("procedure: got '" + request.procedure +
                                  "', expected static, dynamic, lost-motion or torsional");
    }
    if (request.options.contains("seconds")) {
      const auto& v = request.options["seconds"];
      if (!v.is_number() || v.get<double>() <= 0) {
        throw std::invalid_argument("seconds: got " + v.dump() + ", expected a positive number");
      }
    }
    ++checks;
  }

  int runs_launched = 0;
  mutable std::atomic<int> checks{0};
};

}  // namespace wavebench::daemon::testing
