#pragma once
// Every sample to samples.wbs as it is acquired, on the bench thread. The first write that
// fails (disk full, read-only, I/O error, file too large) trips the bench at once: a run whose
// samples are not being recorded must not go on moving it (issue #8). After that, samples are
// counted, not written: a failing disk can be slow to fail again, and the acquisition must not
// wait on it.

#include <cstdint>
#include <string>

#include "wavebench/bench/bench.hpp"
#include "wavebench/storage/sample_log.hpp"

namespace wavebench::runs {

class SampleLogObserver final : public bench::SampleObserver {
 public:
  SampleLogObserver(storage::SampleLogWriter& writer, bench::Bench& bench)
      : writer_(writer), bench_(bench) {}
  void on_sample(const storage::SyncSample& sample) noexcept override;

  bool failed() const { return failed_; }
  // The reason the bench was tripped with, e.g. "sample log: disk full (No space left on
  // device) at sample 12345".
  const std::string& failure() const { return failure_; }
  std::uint64_t samples_not_logged() const { return not_logged_; }

 private:
  void fail(const std::string& what) noexcept;

  storage::SampleLogWriter& writer_;
  bench::Bench& bench_;
  bool failed_ = false;
  std::string failure_;
  std::uint64_t not_logged_ = 0;
  const std::string fallback_reason_ = "sample log: write failed";
};

// "disk full", "file system read-only", ... for an errno of a failed write.
std::string describe_write_error(int error);

}  // namespace wavebench::runs
