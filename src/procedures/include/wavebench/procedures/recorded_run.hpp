#pragma once
// A run in two parts (issue #21, #23): its recording, on the bench thread, which ends with the
// samples log closed and the bench inactive (drive off, brake off), and its post-run stages
// (twin, twin calibration, verdict and results.json, the unit's twin, the report), which work
// on disk and CPU only and may run on any other thread while the bench takes the next unit.
//
// Until finish() has written results.json the run stays `running` in the index (its
// results.json, when written at the recording's end, says "status": "processing"): it is
// never complete or PASS before its results are on disk.
//
// The unit's twin: a run takes the unit twin that is on disk when its recording starts. A
// run recorded while the post-run work of the same unit's previous run is still queued runs
// beside the twin before that run's update; its own post-run update (later in the queue)
// then includes the previous run.

#include <memory>
#include <string>

#include "wavebench/procedures/run_executor.hpp"

namespace wavebench::procedures {

struct RunContext;

class RecordedRun {
 public:
  explicit RecordedRun(std::unique_ptr<RunContext> context);
  ~RecordedRun();
  RecordedRun(RecordedRun&&) noexcept;
  RecordedRun& operator=(RecordedRun&&) noexcept;

  const std::string& run_id() const;
  const std::string& procedure() const;
  const std::string& unit_serial() const;
  // Wall seconds the post-run stages are estimated to take (never much less than they do:
  // post_run_stages.cpp, constants measured on the simulated bench, with a margin).
  double post_run_estimate_s() const;
  // The post-run stages in order, on the calling thread, which must not be the bench's (the
  // stages never call the bench). Progress: phase, fraction of the post-run work, remaining_s.
  // A stage that fails is recorded in the results; when results.json cannot be written the
  // run is finished aborted with the error's text. Call once.
  RunOutcome finish(const ProgressSink& progress = {});

 private:
  std::unique_ptr<RunContext> context_;
};

// The recording: the request checked (std::invalid_argument naming the key, nothing created),
// the run created, the procedure run with every sample logged, the bench deactivated and the
// log closed. A trip is not an exception: the context carries the aborted status and reason.
// Progress: phase, fraction of the recording by time, remaining_s of the recording.
RecordedRun record_run(bench::Bench& bench, storage::RunStore& store, const RunRequest& request,
                       const ProgressSink& progress = {});

}  // namespace wavebench::procedures
