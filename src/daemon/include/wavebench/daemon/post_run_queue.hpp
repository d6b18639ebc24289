#pragma once
// The post-run work of recorded runs (twin, calibration, verdict, results.json, unit twin,
// report: RecordedLaunch::finish), one run at a time in the order recorded, on one worker
// thread at the lowest priority (nice 19): never on the bench thread, which is free for the
// next unit meanwhile. drain() (daemon shutdown) waits until every queued run is finished.

#include <condition_variable>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "wavebench/daemon/run_launcher.hpp"
#include "wavebench/daemon/stated_progress.hpp"

namespace wavebench::daemon {

struct PostRunStatus {
  std::string run_id;
  std::string unit_serial;
  std::string procedure;
  std::string phase;        // "queued" until its turn
  double fraction = 0;      // of its own post-run work
  double remaining_s = -1;  // until its results are written, the runs ahead of it included
};

class PostRunQueue {
 public:
  // Called on the worker when a run's work has ended: its outcome, or the text of what the
  // work threw.
  using Done = std::function<void(const std::string& run_id, const procedures::RunOutcome* outcome,
                                  const std::string& error)>;

  explicit PostRunQueue(Done done);
  ~PostRunQueue();
  PostRunQueue(const PostRunQueue&) = delete;
  PostRunQueue& operator=(const PostRunQueue&) = delete;

  void push(RecordedLaunch run);
  std::vector<PostRunStatus> status() const;
  bool pending(const std::string& run_id) const;
  // Waits until every queued run is finished, then ends the worker. Idempotent.
  void drain();

 private:
  struct Entry {
    RecordedLaunch run;
    std::string phase = "queued";
    StatedProgress progress;
  };
  void worker_main();

  Done done_;
  mutable std::mutex mutex_;
  std::condition_variable wake_;
  std::deque<std::shared_ptr<Entry>> entries_;  // front: the one running (when started)
  bool front_started_ = false;
  bool draining_ = false;
  std::thread worker_;
};

}  // namespace wavebench::daemon
