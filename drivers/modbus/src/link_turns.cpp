#include "wavebench/modbus/link_turns.hpp"

namespace wavebench::modbus {

LinkTurns::Turn LinkTurns::take(TurnPriority priority) {
  std::unique_lock lock(mutex_);
  const auto me = std::this_thread::get_id();
  if (held_ && holder_ == me) return Turn(nullptr);
  if (priority == TurnPriority::safety) {
    ++safety_waiting_;
    changed_.wait(lock, [this] { return !held_; });
    --safety_waiting_;
  } else {
    ++routine_waiting_;
    changed_.wait(lock, [this] { return !held_ && safety_waiting_ == 0; });
    --routine_waiting_;
  }
  held_ = true;
  holder_ = me;
  return Turn(this);
}

void LinkTurns::release() {
  {
    std::lock_guard lock(mutex_);
    held_ = false;
    holder_ = {};
  }
  changed_.notify_all();
}

std::size_t LinkTurns::waiting(TurnPriority priority) const {
  std::lock_guard lock(mutex_);
  return priority == TurnPriority::safety ? safety_waiting_ : routine_waiting_;
}

}  // namespace wavebench::modbus
