#pragma once
// A SampleLogWriter driven by its own thread (issue #9): the acquisition thread only copies a
// sample into a bounded lock-free queue and returns; the writer thread appends, flushes
// (write(2)) and checkpoints (fdatasync(2)), so a slow or stalled disk never holds the SYNC
// cycle. A full queue drops the sample and counts it; nothing is dropped silently.
//
// Threads: try_push() from one producer thread (the bench thread), everything else from the
// owner's thread. The writer is the thread's from construction until finish() returns.

#include <atomic>
#include <boost/lockfree/spsc_queue.hpp>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <thread>

#include "wavebench/storage/sample_log.hpp"

namespace wavebench::storage {

struct SampleLogThreadOptions {
  // 131 s at 1 kHz (10 MB): beyond any disk stall a run should ride through, and room for the
  // simulated clock outrunning the disk.
  std::size_t queue_capacity = std::size_t{1} << 17;
  // The writer thread looks at the queue this often when it is empty: polling means the
  // bench thread makes no system call to wake it.
  std::chrono::microseconds poll_interval{2000};
  // Simulated clock only (0 on the real clock): try_push() waits while more than this many
  // samples are queued instead of letting the bench outrun its log. Waiting costs no bench
  // time there, and a write failure then trips the bench within about as many samples as on
  // the real clock, instead of after whatever the simulation ran ahead meanwhile.
  std::size_t lockstep_backlog = 0;
};

class SampleLogThread {
 public:
  // Called once, on the writer thread, with the writer's first failure: the errno (0 when the
  // failure was not a system error) and its message. Samples after it are counted, not written.
  using FailureSink = std::function<void(int error, const std::string& what)>;

  SampleLogThread(SampleLogWriter& writer, FailureSink on_failure,
                  SampleLogThreadOptions options = {});
  ~SampleLogThread();
  SampleLogThread(const SampleLogThread&) = delete;
  SampleLogThread& operator=(const SampleLogThread&) = delete;

  // Producer side: never waits (but see lockstep_backlog), never allocates. False when the
  // queue is full (counted).
  bool try_push(const SyncSample& sample) noexcept;

  // Writes everything queued, then joins the thread. Idempotent. Push nothing after it. The
  // writer is the caller's again afterwards (close() it).
  void finish();

  std::uint64_t samples_pushed() const noexcept { return pushed_.load(std::memory_order_relaxed); }
  // Queue full: never reached the writer.
  std::uint64_t samples_dropped() const noexcept {
    return dropped_.load(std::memory_order_relaxed);
  }
  // Reached the writer thread after (or with) a failed write: not in the file.
  std::uint64_t samples_not_written() const noexcept {
    return not_written_.load(std::memory_order_relaxed);
  }

 private:
  void run() noexcept;
  void write_batch(const SyncSample* samples, std::size_t count) noexcept;
  void flush_if_due() noexcept;
  void fail(int error, const std::string& what) noexcept;

  SampleLogWriter& writer_;
  FailureSink on_failure_;
  SampleLogThreadOptions options_;
  boost::lockfree::spsc_queue<SyncSample> queue_;
  std::atomic<std::uint64_t> pushed_{0};
  std::atomic<std::uint64_t> dropped_{0};
  std::atomic<std::uint64_t> not_written_{0};
  std::atomic<bool> stopping_{false};
  bool failed_ = false;  // writer thread only
  bool finished_ = false;
  std::thread thread_;  // last: starts after everything it uses
};

}  // namespace wavebench::storage
