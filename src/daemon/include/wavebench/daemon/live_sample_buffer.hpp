#pragma once
// The latest samples for GET /api/live: a ring buffer fed on the bench thread, read from the
// API threads. Each sample gets a sequence number that only grows, so a client asks for what
// arrived since the last number it saw and learns how many it missed.

#include <cstddef>
#include <cstdint>
#include <mutex>
#include <vector>

#include "wavebench/bench/bench.hpp"

namespace wavebench::daemon {

struct LiveSample {
  std::uint64_t seq = 0;
  storage::SyncSample sample;
};

struct LiveSlice {
  std::vector<LiveSample> samples;  // oldest first
  std::uint64_t next_seq = 0;       // ask with since = next_seq to continue
  std::uint64_t missed = 0;         // samples after `since` that had left the buffer
};

class LiveSampleBuffer : public bench::SampleObserver {
 public:
  explicit LiveSampleBuffer(std::size_t capacity = 8192);

  void on_sample(const storage::SyncSample& sample) noexcept override;
  // Samples with seq >= since, at most `limit` of the newest ones.
  LiveSlice since(std::uint64_t since, std::size_t limit) const;
  std::uint64_t total() const;

 private:
  mutable std::mutex mutex_;
  std::vector<storage::SyncSample> ring_;
  std::uint64_t next_seq_ = 0;  // seq of the next sample; also the count so far
};

}  // namespace wavebench::daemon
