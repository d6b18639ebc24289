#include "wavebench/daemon/publishing_run_launcher.hpp"

namespace wavebench::daemon {

PublishingRunLauncher::PublishingRunLauncher(std::unique_ptr<RunLauncher> inner,
                                             fleet::Outbox& outbox)
    : inner_(std::move(inner)), outbox_(outbox) {}

procedures::RunOutcome PublishingRunLauncher::launch(bench::Bench& bench, storage::RunStore& store,
                                               const procedures::RunRequest& request,
                                               const procedures::ProgressSink& progress) {
  // A launch that throws after creating its run leaves it `running` in the index: the next
  // start marks it incomplete and the outbox's backlog sends it then.
  auto outcome = inner_->launch(bench, store, request, progress);
  outbox_.enqueue(outcome.run_id);
  return outcome;
}

RecordedLaunch PublishingRunLauncher::record(bench::Bench& bench, storage::RunStore& store,
                                             const procedures::RunRequest& request,
                                             const procedures::ProgressSink& progress) {
  auto recorded = inner_->record(bench, store, request, progress);
  recorded.finish = [finish = std::move(recorded.finish),
                     &outbox = outbox_](const procedures::ProgressSink& p) {
    auto outcome = finish(p);
    outbox.enqueue(outcome.run_id);
    return outcome;
  };
  return recorded;
}

void PublishingRunLauncher::check(const procedures::RunRequest& request,
                                  const bench::BenchDescription& bench, std::size_t extra_channels,
                                  const std::filesystem::path& runs_root) const {
  inner_->check(request, bench, extra_channels, runs_root);
}

}  // namespace wavebench::daemon
