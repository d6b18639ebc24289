#include "sample_log_observer.hpp"

#include <cerrno>
#include <system_error>

namespace wavebench::runs {

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

void SampleLogObserver::on_sample(const storage::SyncSample& sample) noexcept {
  if (failed_) {
    ++not_logged_;
    return;
  }
  std::string what;
  try {
    try {
      writer_.append(sample);
      writer_.flush_if_due();
      return;
    } catch (const std::system_error& e) {
      what = describe_write_error(e.code().value()) + " (" + e.code().message() + ")";
    } catch (const std::exception& e) {
      what = e.what();
    }
  } catch (...) {  // NOLINT(bugprone-empty-catch): out of memory describing it; fail() copes
  }
  ++not_logged_;
  fail(what);
}

void SampleLogObserver::fail(const std::string& what) noexcept {
  failed_ = true;
  try {
    // The first record that did not reach the file: the log holds [0, this) at least.
    failure_ = "sample log: " + (what.empty() ? std::string("write failed") : what) +
               " at sample " + std::to_string(writer_.records_flushed());
    bench_.request_stop(failure_);
  } catch (...) {
    bench_.request_stop(fallback_reason_);  // the trip matters more than its wording
  }
}

}  // namespace wavebench::runs
