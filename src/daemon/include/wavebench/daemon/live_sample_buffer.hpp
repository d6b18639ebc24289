#pragma once
// The latest samples for GET /api/live: a ring buffer fed on the bench thread, read from the
// API threads. Each sample gets a sequence number that only grows, so a client asks for what
// arrived since the last number it saw and learns how many it missed.
//
// A seqlock per slot, no mutex: the bench thread never waits for a reader (issue #9); a
// reader that raced the writer on a slot counts that sample as missed instead of waiting.

#include <array>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <memory>
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

  // One writer (the bench thread).
  void on_sample(const storage::SyncSample& sample) noexcept override;
  // Any number of readers. Samples with seq >= since, at most `limit` of the newest ones.
  LiveSlice since(std::uint64_t since, std::size_t limit) const;
  std::uint64_t total() const;

 private:
  static constexpr std::size_t kWords =
      (sizeof(storage::SyncSample) + sizeof(std::uint64_t) - 1) / sizeof(std::uint64_t);
  struct Slot {
    // 2·seq + 1 while sample seq is being written, 2·seq + 2 once it is complete.
    std::atomic<std::uint64_t> stamp{0};
    // The sample's bytes in atomic words, so that a racing reader is not a data race.
    std::array<std::atomic<std::uint64_t>, kWords> words{};
  };
  bool read_slot(std::uint64_t seq, storage::SyncSample& out) const;

  std::unique_ptr<Slot[]> slots_;
  std::size_t capacity_;
  std::atomic<std::uint64_t> next_seq_{0};  // seq of the next sample; also the count so far
};

}  // namespace wavebench::daemon
