#pragma once
// How the bench thread starts a run. The daemon calls procedures::execute_run through this seam so
// that its own logic can be tested with a stand-in.

#include <cstddef>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>

#include "wavebench/bench/bench.hpp"
#include "wavebench/procedures/run_executor.hpp"
#include "wavebench/storage/run_store.hpp"

namespace wavebench::daemon {

// A run whose recording has ended (the bench inactive, its samples on disk) and whose post-run
// work is still to do: `finish` runs it, on the post-run worker, never on the bench thread.
struct RecordedLaunch {
  std::string run_id;
  std::string procedure;
  std::string unit_serial;
  double post_run_estimate_s = 0;  // wall seconds
  std::function<procedures::RunOutcome(const procedures::ProgressSink&)> finish;
};

class RunLauncher {
 public:
  virtual ~RunLauncher() = default;
  // Same contract as procedures::execute_run: std::invalid_argument for a bad request (nothing
  // created), a bench trip returns an aborted outcome.
  virtual procedures::RunOutcome launch(bench::Bench& bench, storage::RunStore& store,
                                  const procedures::RunRequest& request,
                                  const procedures::ProgressSink& progress) = 0;
  // The recording only (procedures::record_run); the rest in the returned finish. By default the
  // whole of launch(), with nothing left to finish (the stand-ins of the tests).
  virtual RecordedLaunch record(bench::Bench& bench, storage::RunStore& store,
                                const procedures::RunRequest& request,
                                const procedures::ProgressSink& progress) {
    auto outcome = launch(bench, store, request, progress);
    return {outcome.run_id, request.procedure, request.unit_serial, 0,
            [outcome](const procedures::ProgressSink&) { return outcome; }};
  }
  // The checks launch() makes before anything is created or moves, without the bench: called
  // on an API thread before a request is queued, so a malformed or over-limit request is
  // refused (400) whatever the bench is doing. Thread-safe. Throws std::invalid_argument
  // naming the key, the value and what was expected.
  virtual void check(const procedures::RunRequest& request, const bench::BenchDescription& bench,
                     std::size_t extra_channels, const std::filesystem::path& runs_root) const = 0;
};

// The real one, procedures::execute_run (src/executor_run_launcher.cpp, built with the executable:
// the library itself does not link the run executor).
std::unique_ptr<RunLauncher> make_executor_run_launcher();

}  // namespace wavebench::daemon
