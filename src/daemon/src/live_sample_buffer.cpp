#include "wavebench/daemon/live_sample_buffer.hpp"

#include <algorithm>
#include <cstring>
#include <stdexcept>
#include <type_traits>

namespace wavebench::daemon {

static_assert(std::is_trivially_copyable_v<storage::SyncSample>,
              "live samples are copied word by word");

LiveSampleBuffer::LiveSampleBuffer(std::size_t capacity)
    : slots_(capacity == 0 ? nullptr : std::make_unique<Slot[]>(capacity)), capacity_(capacity) {
  if (capacity == 0) throw std::invalid_argument("live sample buffer: capacity 0");
}

void LiveSampleBuffer::on_sample(const storage::SyncSample& sample) noexcept {
  const std::uint64_t seq = next_seq_.load(std::memory_order_relaxed);
  Slot& slot = slots_[seq % capacity_];
  std::array<std::uint64_t, kWords> words{};
  std::memcpy(words.data(), &sample, sizeof sample);
  slot.stamp.store(2 * seq + 1, std::memory_order_relaxed);
  std::atomic_thread_fence(std::memory_order_release);  // the odd stamp before the new words
  for (std::size_t i = 0; i < kWords; ++i) slot.words[i].store(words[i], std::memory_order_relaxed);
  slot.stamp.store(2 * seq + 2, std::memory_order_release);
  next_seq_.store(seq + 1, std::memory_order_release);
}

bool LiveSampleBuffer::read_slot(std::uint64_t seq, storage::SyncSample& out) const {
  const Slot& slot = slots_[seq % capacity_];
  const std::uint64_t before = slot.stamp.load(std::memory_order_acquire);
  if (before != 2 * seq + 2) return false;  // being overwritten or already overwritten
  std::array<std::uint64_t, kWords> words{};
  for (std::size_t i = 0; i < kWords; ++i) words[i] = slot.words[i].load(std::memory_order_relaxed);
  std::atomic_thread_fence(std::memory_order_acquire);  // the words before the second look
  if (slot.stamp.load(std::memory_order_relaxed) != before) return false;
  std::memcpy(static_cast<void*>(&out), words.data(), sizeof out);  // trivially copyable
  return true;
}

LiveSlice LiveSampleBuffer::since(std::uint64_t since, std::size_t limit) const {
  LiveSlice slice;
  const std::uint64_t next = next_seq_.load(std::memory_order_acquire);
  slice.next_seq = next;
  const std::uint64_t oldest = next > capacity_ ? next - capacity_ : 0;
  std::uint64_t first = std::max(since, oldest);
  if (first > since) slice.missed = first - since;
  if (first >= next) return slice;
  // The newest `limit` of what is there; what lies before them counts as missed.
  if (limit > 0 && next - first > limit) {
    slice.missed += next - limit - first;
    first = next - limit;
  }
  slice.samples.reserve(static_cast<std::size_t>(next - first));
  for (std::uint64_t seq = first; seq < next; ++seq) {
    LiveSample live{seq, {}};
    // The writer lapped the reader on this slot: the sample is gone, as if it had left.
    if (read_slot(seq, live.sample)) {
      slice.samples.push_back(live);
    } else {
      ++slice.missed;
    }
  }
  return slice;
}

std::uint64_t LiveSampleBuffer::total() const {
  return next_seq_.load(std::memory_order_acquire);
}

}  // namespace wavebench::daemon
