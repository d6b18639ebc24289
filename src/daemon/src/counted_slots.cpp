#include "wavebench/daemon/counted_slots.hpp"

namespace wavebench::daemon {

std::shared_ptr<void> CountedSlots::admit() {
  auto count = count_;
  if (count->fetch_add(1) >= max_) {
    count->fetch_sub(1);
    return nullptr;
  }
  // Not null (a null shared_ptr tests false even with a deleter); the deleter only counts.
  return std::shared_ptr<void>(count.get(), [count](void*) { count->fetch_sub(1); });
}

}  // namespace wavebench::daemon
