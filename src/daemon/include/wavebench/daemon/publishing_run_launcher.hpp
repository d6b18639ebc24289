#pragma once
// A run launcher that hands every run it finished to the outbox of the shared results store
// (issue #13): the run is on disk and in the index when launch() returns; the outbox sends it
// from its own thread. Runs the same checks and runs as the launcher it wraps.

#include <memory>

#include "wavebench/daemon/run_launcher.hpp"
#include "wavebench/fleet/outbox.hpp"

namespace wavebench::daemon {

class PublishingRunLauncher : public RunLauncher {
 public:
  PublishingRunLauncher(std::unique_ptr<RunLauncher> inner, fleet::Outbox& outbox);

  procedures::RunOutcome launch(bench::Bench& bench, storage::RunStore& store,
                          const procedures::RunRequest& request,
                          const procedures::ProgressSink& progress) override;
  // The run goes to the outbox when its post-run work has finished it.
  RecordedLaunch record(bench::Bench& bench, storage::RunStore& store,
                        const procedures::RunRequest& request,
                        const procedures::ProgressSink& progress) override;
  void check(const procedures::RunRequest& request, const bench::BenchDescription& bench,
             std::size_t extra_channels, const std::filesystem::path& runs_root) const override;

 private:
  std::unique_ptr<RunLauncher> inner_;
  fleet::Outbox& outbox_;
};

}  // namespace wavebench::daemon
