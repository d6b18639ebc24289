#pragma once
// Reads whose cost grows with the data (sample pages, run details) run on their own threads at
// a lower scheduling priority (nice +10), at most `threads` at a time; a read that finds them
// all busy is refused at once. On a 2-core bench PC two readers could otherwise take both
// cores, and status, abort and stop would wait behind them.

#include <condition_variable>
#include <deque>
#include <functional>
#include <mutex>
#include <optional>
#include <thread>
#include <vector>

#include "wavebench/daemon/daemon_api.hpp"

namespace wavebench::daemon {

class LowPriorityReads {
 public:
  explicit LowPriorityReads(int threads);
  ~LowPriorityReads();
  LowPriorityReads(const LowPriorityReads&) = delete;
  LowPriorityReads& operator=(const LowPriorityReads&) = delete;

  // Runs `read` on a reader thread and returns its answer; std::nullopt when every reader is
  // busy. Exceptions from `read` come back as a 500 answer.
  std::optional<ApiResponse> run(const std::function<ApiResponse()>& read);

 private:
  struct Task;
  void reader_main();

  std::mutex mutex_;
  std::condition_variable wake_;
  std::deque<Task*> queue_;
  int idle_;  // threads not running a read
  bool stopping_ = false;
  std::vector<std::thread> threads_;
};

}  // namespace wavebench::daemon
