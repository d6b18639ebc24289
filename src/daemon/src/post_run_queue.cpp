#include "wavebench/daemon/post_run_queue.hpp"

#include <spdlog/spdlog.h>
#include <sys/resource.h>
#include <unistd.h>

#include <exception>

namespace wavebench::daemon {

PostRunQueue::PostRunQueue(Done done) : done_(std::move(done)) {
  worker_ = std::thread([this] { worker_main(); });
}

PostRunQueue::~PostRunQueue() {
  drain();
}

void PostRunQueue::push(RecordedLaunch run) {
  auto entry = std::make_shared<Entry>();
  entry->progress.report(0, run.post_run_estimate_s);
  entry->run = std::move(run);
  {
    std::lock_guard lock(mutex_);
    entries_.push_back(std::move(entry));
  }
  wake_.notify_all();
}

std::vector<PostRunStatus> PostRunQueue::status() const {
  std::lock_guard lock(mutex_);
  std::vector<PostRunStatus> out;
  const auto now = StatedProgress::Clock::now();
  double ahead = 0;  // the time left of the runs before this one
  for (std::size_t i = 0; i < entries_.size(); ++i) {
    const auto& e = *entries_[i];
    const bool running = i == 0 && front_started_;
    const auto p = running ? e.progress.at(now) : ProgressNow{0, e.run.post_run_estimate_s};
    const double own = std::max(0.0, p.remaining_s);
    out.push_back(
        {e.run.run_id, e.run.unit_serial, e.run.procedure, e.phase, p.fraction, ahead + own});
    ahead += own;
  }
  return out;
}

bool PostRunQueue::pending(const std::string& run_id) const {
  std::lock_guard lock(mutex_);
  for (const auto& e : entries_) {
    if (e->run.run_id == run_id) return true;
  }
  return false;
}

void PostRunQueue::drain() {
  {
    std::lock_guard lock(mutex_);
    draining_ = true;
  }
  wake_.notify_all();
  if (worker_.joinable() && worker_.get_id() != std::this_thread::get_id()) worker_.join();
}

void PostRunQueue::worker_main() {
  // The lowest priority: the bench thread and the API come first on a busy machine (Linux
  // nice is per thread). Failing to lower it changes nothing else.
  (void)::setpriority(PRIO_PROCESS, static_cast<id_t>(::gettid()), 19);
  std::unique_lock lock(mutex_);
  for (;;) {
    wake_.wait(lock, [&] { return !entries_.empty() || draining_; });
    if (entries_.empty()) return;  // draining, nothing left
    auto entry = entries_.front();
    front_started_ = true;
    lock.unlock();
    const auto& id = entry->run.run_id;
    try {
      const auto outcome = entry->run.finish([this, &entry](const procedures::RunProgress& p) {
        std::lock_guard progress_lock(mutex_);
        entry->phase = p.phase;
        entry->progress.report(p.fraction, p.remaining_s);
      });
      done_(id, &outcome, "");
    } catch (const std::exception& e) {
      spdlog::error("run {}: post-run work failed: {}", id, e.what());
      done_(id, nullptr, e.what());
    }
    lock.lock();
    entries_.pop_front();
    front_started_ = false;
  }
}

}  // namespace wavebench::daemon
