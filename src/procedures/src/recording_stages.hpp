#pragma once
// The stages that run while the bench records (the first part of recorded_run.hpp), in the
// order recording_stages() makes them: the results' head, the sample log, the twin beside the
// bench. record_run() is the loop over them:
//
//   start(c, bench)   each in order, before the procedure moves anything; a stage that the
//                     run cannot go without aborts the run (c.abort_with), and the stages
//                     after it and the procedure then do nothing
//   on_sample(s)      the observe hook, on the bench thread, once per SYNC cycle while the
//                     procedure runs (for the stages whose observes() is true after start)
//   finish(c)         the procedure is over and the samples no longer come; the bench is
//                     still active (so a trip a stage asked for is still the bench's)
//   close(c, bench)   after the bench is deactivated: files closed, figures into results
//
// Each stage is a class with its own state, so that each can be started, fed samples and
// finished alone (tests/procedures/recording_stages_test.cpp). The twin's draining is the post-run
// "twin" stage (post_run_stages.hpp): it has its own progress phase and time estimate.

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "run_context.hpp"
#include "wavebench/bench/bench.hpp"

namespace wavebench::procedures {

class RecordingStage : public bench::SampleObserver {
 public:
  virtual const char* name() const = 0;
  virtual void start(RunContext& c, bench::Bench& bench) = 0;
  // Whether on_sample() wants the samples (after start(); false when the stage is off).
  virtual bool observes() const { return false; }
  void on_sample(const storage::SyncSample& /*sample*/) noexcept override {}
  virtual void finish(RunContext& /*c*/) {}
  virtual void close(RunContext& /*c*/, const bench::Bench& /*bench*/) {}
  // Why this stage tripped the bench, when it did: the run's reason instead of the trip's
  // own text ("operator abort" of a trip the sample log asked for says less).
  virtual std::optional<std::string> trip_reason() const { return std::nullopt; }
};

// results.json's head: what ran, on which bench, for which unit and spec, by which software.
class ResultsHeadStage final : public RecordingStage {
 public:
  const char* name() const override { return "results head"; }
  void start(RunContext& c, bench::Bench& bench) override;
};

// samples.wbs: every sample as it is acquired (sample_log_observer.hpp). Not created: the
// run is aborted before anything moved. A write that fails trips the bench.
class SampleLogStage final : public RecordingStage {
 public:
  SampleLogStage();
  ~SampleLogStage() override;
  const char* name() const override { return "sample log"; }
  void start(RunContext& c, bench::Bench& bench) override;
  bool observes() const override;
  void on_sample(const storage::SyncSample& sample) noexcept override;
  void finish(RunContext& c) override;
  void close(RunContext& c, const bench::Bench& bench) override;
  std::optional<std::string> trip_reason() const override;

 private:
  struct Log;
  std::unique_ptr<Log> log_;
};

// The twin beside the bench (twin_beside_bench.hpp): the unit's own twin when it has one on
// disk, else the bench's nominal case; fed every sample, drained after the recording.
class TwinBesideBenchStage final : public RecordingStage {
 public:
  const char* name() const override { return "twin beside the bench"; }
  void start(RunContext& c, bench::Bench& bench) override;
  bool observes() const override { return twin_ != nullptr; }
  void on_sample(const storage::SyncSample& sample) noexcept override;

 private:
  twin::TwinBesideBench* twin_ = nullptr;  // the context's (c.twin_beside), once started
};

std::vector<std::unique_ptr<RecordingStage>> recording_stages();

}  // namespace wavebench::procedures
