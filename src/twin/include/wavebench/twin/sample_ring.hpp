#pragma once
// A bounded single-producer/single-consumer ring: the bench thread pushes, the twin thread
// pops. push() never waits: on a full ring it returns false and the caller counts a drop.

#include <atomic>
#include <cstddef>
#include <vector>

namespace wavebench::twin {

template <class T>
class SampleRing {
 public:
  // Capacity rounds up to a power of two (at least 2).
  explicit SampleRing(std::size_t capacity) {
    std::size_t n = 2;
    while (n < capacity) n *= 2;
    slots_.resize(n);
    mask_ = n - 1;
  }
  SampleRing(const SampleRing&) = delete;
  SampleRing& operator=(const SampleRing&) = delete;

  std::size_t capacity() const { return slots_.size(); }

  // Producer side.
  bool try_push(const T& value) noexcept {
    const std::size_t head = head_.load(std::memory_order_relaxed);
    if (head - tail_.load(std::memory_order_acquire) >= slots_.size()) return false;
    slots_[head & mask_] = value;
    head_.store(head + 1, std::memory_order_seq_cst);
    return true;
  }

  // Consumer side: appends up to `max` values to `out`, returns how many.
  template <class Container>
  std::size_t pop_into(Container& out, std::size_t max) {
    const std::size_t tail = tail_.load(std::memory_order_relaxed);
    const std::size_t head = head_.load(std::memory_order_acquire);
    std::size_t n = head - tail;
    if (n > max) n = max;
    for (std::size_t i = 0; i < n; ++i) out.push_back(slots_[(tail + i) & mask_]);
    tail_.store(tail + n, std::memory_order_release);
    return n;
  }

  bool empty() const noexcept {
    return head_.load(std::memory_order_seq_cst) == tail_.load(std::memory_order_acquire);
  }

 private:
  std::vector<T> slots_;
  std::size_t mask_ = 0;
  alignas(64) std::atomic<std::size_t> head_{0};  // next slot to write (producer)
  alignas(64) std::atomic<std::size_t> tail_{0};  // next slot to read (consumer)
};

}  // namespace wavebench::twin
