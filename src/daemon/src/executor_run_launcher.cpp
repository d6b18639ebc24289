#include "wavebench/daemon/run_launcher.hpp"
#include "wavebench/procedures/recorded_run.hpp"
#include "wavebench/procedures/run_request_check.hpp"

namespace wavebench::daemon {

namespace {

class ExecutorRunLauncher : public RunLauncher {
 public:
  procedures::RunOutcome launch(bench::Bench& bench, storage::RunStore& store,
                          const procedures::RunRequest& request,
                          const procedures::ProgressSink& progress) override {
    return procedures::execute_run(bench, store, request, progress);
  }
  RecordedLaunch record(bench::Bench& bench, storage::RunStore& store,
                        const procedures::RunRequest& request,
                        const procedures::ProgressSink& progress) override {
    auto recorded =
        std::make_shared<procedures::RecordedRun>(procedures::record_run(bench, store, request, progress));
    return {recorded->run_id(), recorded->procedure(), recorded->unit_serial(),
            recorded->post_run_estimate_s(),
            [recorded](const procedures::ProgressSink& p) { return recorded->finish(p); }};
  }
  void check(const procedures::RunRequest& request, const bench::BenchDescription& bench,
             std::size_t extra_channels, const std::filesystem::path& runs_root) const override {
    procedures::check_run_request(request, bench, extra_channels, runs_root);
  }
};

}  // namespace

std::unique_ptr<RunLauncher> make_executor_run_launcher() {
  return std::make_unique<ExecutorRunLauncher>();
}

}  // namespace wavebench::daemon
