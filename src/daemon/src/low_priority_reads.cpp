#include "wavebench/daemon/low_priority_reads.hpp"

#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <future>

namespace wavebench::daemon {

struct LowPriorityReads::Task {
  const std::function<ApiResponse()>* read;
  std::promise<ApiResponse> done;
};

LowPriorityReads::LowPriorityReads(int threads) : idle_(threads) {
  for (int i = 0; i < threads; ++i) threads_.emplace_back([this] { reader_main(); });
}

LowPriorityReads::~LowPriorityReads() {
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_all();
  for (auto& t : threads_) t.join();
}

std::optional<ApiResponse> LowPriorityReads::run(const std::function<ApiResponse()>& read) {
  Task task{&read, {}};
  auto answer = task.done.get_future();
  {
    std::lock_guard lock(mutex_);
    if (stopping_ || idle_ <= static_cast<int>(queue_.size())) return std::nullopt;
    queue_.push_back(&task);
  }
  wake_.notify_one();
  return answer.get();
}

void LowPriorityReads::reader_main() {
  // Linux keeps a nice value per thread; raising it needs no privilege. Failure only means
  // the reads compete at normal priority.
  (void)::setpriority(PRIO_PROCESS, static_cast<id_t>(::syscall(SYS_gettid)), 10);
  std::unique_lock lock(mutex_);
  for (;;) {
    wake_.wait(lock, [&] { return stopping_ || !queue_.empty(); });
    if (queue_.empty()) return;  // stopping, nothing left to answer
    Task* task = queue_.front();
    queue_.pop_front();
    --idle_;
    lock.unlock();
    ApiResponse answer;
    try {
      answer = (*task->read)();
    } catch (const std::exception& e) {
      answer = api_error(500, "internal error", e.what());
    } catch (...) {
      answer = api_error(500, "internal error", "unknown exception");
    }
    // The reader counts as idle again before its caller learns the answer: a caller that
    // starts its next read at once must not find this reader still busy and be refused.
    lock.lock();
    ++idle_;
    task->done.set_value(std::move(answer));
  }
}

}  // namespace wavebench::daemon
