#pragma once
// At most `max` of something at once (live streams, export downloads): admit() gives a slot
// that frees itself when its last copy goes, or nullptr when all are taken.

#include <atomic>
#include <cstddef>
#include <memory>

namespace wavebench::daemon {

class CountedSlots {
 public:
  explicit CountedSlots(std::size_t max) : max_(max) {}
  std::shared_ptr<void> admit();
  std::size_t max() const { return max_; }
  std::size_t in_use() const { return count_->load(); }

 private:
  std::size_t max_;
  std::shared_ptr<std::atomic<std::size_t>> count_ = std::make_shared<std::atomic<std::size_t>>(0);
};

}  // namespace wavebench::daemon
