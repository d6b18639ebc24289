#include "wavebench/daemon/live_sample_buffer.hpp"

#include <algorithm>
#include <stdexcept>

namespace wavebench::daemon {

LiveSampleBuffer::LiveSampleBuffer(std::size_t capacity) : ring_(capacity) {
  if (capacity == 0) throw std::invalid_argument("live sample buffer: capacity 0");
}

void LiveSampleBuffer::on_sample(const storage::SyncSample& sample) noexcept {
  std::lock_guard lock(mutex_);
  ring_[next_seq_ % ring_.size()] = sample;
  ++next_seq_;
}

LiveSlice LiveSampleBuffer::since(std::uint64_t since, std::size_t limit) const {
  std::lock_guard lock(mutex_);
  LiveSlice slice;
  slice.next_seq = next_seq_;
  const std::uint64_t oldest = next_seq_ > ring_.size() ? next_seq_ - ring_.size() : 0;
  std::uint64_t first = std::max(since, oldest);
  if (first > since) slice.missed = first - since;
  if (first >= next_seq_) return slice;
  // The newest `limit` of what is there; what lies before them counts as missed.
  if (limit > 0 && next_seq_ - first > limit) {
    slice.missed += next_seq_ - limit - first;
    first = next_seq_ - limit;
  }
  slice.samples.reserve(static_cast<std::size_t>(next_seq_ - first));
  for (std::uint64_t seq = first; seq < next_seq_; ++seq) {
    slice.samples.push_back({seq, ring_[seq % ring_.size()]});
  }
  return slice;
}

std::uint64_t LiveSampleBuffer::total() const {
  std::lock_guard lock(mutex_);
  return next_seq_;
}

}  // namespace wavebench::daemon
