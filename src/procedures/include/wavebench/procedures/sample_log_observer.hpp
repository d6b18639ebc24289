#pragma once
// Every sample to samples.wbs as it is acquired. On the bench thread the observer only copies
// the sample into the log thread's bounded queue (storage::SampleLogThread); the disk is
// written and synced on that thread, so a slow disk never holds the SYNC cycle (issue #9). A
// full queue drops the sample and counts it (samples_dropped(), in the run's results). On the
// simulated clock the bench waits for the log thread instead (lockstep_backlog): that costs no
// bench time, and the bench cannot run ahead of its log.
//
// The first write that fails (disk full, read-only, I/O error, file too large) trips the bench
// from the log thread: a run whose samples are not being recorded must not go on moving it
// (issue #8). After that, samples are counted, not written: a failing disk can be slow to fail
// again.

#include <atomic>
#include <cstdint>
#include <string>

#include "wavebench/bench/bench.hpp"
#include "wavebench/storage/sample_log.hpp"
#include "wavebench/storage/sample_log_thread.hpp"

namespace wavebench::procedures {

class SampleLogObserver final : public bench::SampleObserver {
 public:
  SampleLogObserver(storage::SampleLogWriter& writer, bench::Bench& bench,
                    storage::SampleLogThreadOptions options = {});
  void on_sample(const storage::SyncSample& sample) noexcept override;

  // After the observer is removed from the bench: writes what is queued and joins the log
  // thread. A write failing from here on no longer trips the bench (the motion is over); it
  // shows in failed() for the run to be aborted with. The writer is the caller's again.
  void finish();

  // Safe from any thread; failure() once failed() is true.
  bool failed() const { return failed_.load(std::memory_order_acquire); }
  // The reason the bench was tripped with, e.g. "sample log: disk full (No space left on
  // device) at sample 12345".
  const std::string& failure() const { return failure_; }
  // Not in the file because of a write failure.
  std::uint64_t samples_not_logged() const { return thread_.samples_not_written(); }
  // Not in the file because the log thread's queue was full.
  std::uint64_t samples_dropped() const { return thread_.samples_dropped(); }

 private:
  void fail(int error, const std::string& what) noexcept;  // on the log thread

  storage::SampleLogWriter& writer_;
  bench::Bench& bench_;
  std::atomic<bool> failed_{false};
  std::atomic<bool> motion_over_{false};
  std::string failure_;
  const std::string fallback_reason_ = "sample log: write failed";
  storage::SampleLogThread thread_;  // last: its thread calls fail()
};

// "disk full", "file system read-only", ... for an errno of a failed write.
std::string describe_write_error(int error);

}  // namespace wavebench::procedures
