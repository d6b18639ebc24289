#include "wavebench/procedures/sample_log_observer.hpp"

#include <cerrno>
#include <system_error>

namespace wavebench::procedures {

std::string describe_write_error(int error) {
  switch (error) {
    case ENOSPC:
      return "disk full";
    case EDQUOT:
      return "disk quota exceeded";
    case EROFS:
      return "file system read-only";
    case EIO:
      return "I/O error";
    case EFBIG:
      return "file size limit reached";
    default:
      return "write failed";
  }
}

namespace {

// On the simulated clock the bench must not outrun its log (lockstep_backlog says why).
storage::SampleLogThreadOptions for_clock(storage::SampleLogThreadOptions options,
                                          const bench::Bench& bench) {
  if (bench.description().simulated_clock) {
    options.lockstep_backlog = 32;
    options.poll_interval = std::chrono::microseconds(250);
  }
  return options;
}

}  // namespace

SampleLogObserver::SampleLogObserver(storage::SampleLogWriter& writer, bench::Bench& bench,
                                     storage::SampleLogThreadOptions options)
    : writer_(writer),
      bench_(bench),
      thread_(
          writer, [this](int error, const std::string& what) { fail(error, what); },
          for_clock(options, bench)) {}

void SampleLogObserver::on_sample(const storage::SyncSample& sample) noexcept {
  thread_.try_push(sample);  // a full queue is counted by the thread
}

void SampleLogObserver::finish() {
  motion_over_.store(true, std::memory_order_release);
  thread_.finish();
}

void SampleLogObserver::fail(int error, const std::string& what) noexcept {
  try {
    std::string why = error != 0 ? describe_write_error(error) + " (" +
                                       std::generic_category().message(error) + ")"
                                 : what;
    // The first record that did not reach the file: the log holds [0, this) at least.
    failure_ = "sample log: " + (why.empty() ? std::string("write failed") : why) + " at sample " +
               std::to_string(writer_.records_flushed());
  } catch (...) {
    try {
      failure_ = fallback_reason_;  // the trip matters more than its wording
    } catch (...) {  // NOLINT(bugprone-empty-catch): failure() stays empty; the trip still goes
    }
  }
  failed_.store(true, std::memory_order_release);
  if (!motion_over_.load(std::memory_order_acquire)) {
    bench_.request_stop(failure_.empty() ? fallback_reason_ : failure_);
  }
}

}  // namespace wavebench::procedures
