#pragma once
// A disk that fills up, without root or a mount: RLIMIT_FSIZE caps the size of every file this
// process writes, and a write past it fails with EFBIG (SIGXFSZ ignored) as a write to a full
// disk fails with ENOSPC. For the lifetime of the guard; the soft limit is restored after.
// Files already larger than the cap cannot grow; small ones (an index, a status file) still
// can, which is what a nearly full disk looks like to a run.
#include <sys/resource.h>

#include <csignal>
#include <stdexcept>

namespace wavebench::testing {

class FileSizeLimit {
 public:
  explicit FileSizeLimit(rlim_t max_bytes) {
    if (::getrlimit(RLIMIT_FSIZE, &saved_) != 0) throw std::runtime_error("getrlimit");
    previous_handler_ = std::signal(SIGXFSZ, SIG_IGN);
    rlimit limit = saved_;
    limit.rlim_cur = max_bytes;
    if (::setrlimit(RLIMIT_FSIZE, &limit) != 0) throw std::runtime_error("setrlimit");
  }
  ~FileSizeLimit() {
    ::setrlimit(RLIMIT_FSIZE, &saved_);
    std::signal(SIGXFSZ, previous_handler_);
  }
  FileSizeLimit(const FileSizeLimit&) = delete;
  FileSizeLimit& operator=(const FileSizeLimit&) = delete;

 private:
  rlimit saved_{};
  void (*previous_handler_)(int) = SIG_DFL;
};

}  // namespace wavebench::testing
