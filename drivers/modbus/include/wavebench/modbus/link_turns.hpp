#pragma once
// Turns on one Modbus link shared by several threads (one RS-485 line has one master): one
// turn at a time, and a safety turn goes before every routine turn that is waiting, so the
// brake's safe-state write waits at most for the transaction already on the wire, never for a
// queue of polls (issue #9). A thread that holds a turn may take another: it is its own.
//
// Hand-written because the priority rule is the point; a std::mutex alone has no order.

#include <condition_variable>
#include <cstddef>
#include <mutex>
#include <thread>

namespace wavebench::modbus {

enum class TurnPriority { routine, safety };

class LinkTurns {
 public:
  class Turn {
   public:
    Turn(Turn&& other) noexcept : turns_(other.turns_) { other.turns_ = nullptr; }
    Turn& operator=(Turn&&) = delete;
    Turn(const Turn&) = delete;
    Turn& operator=(const Turn&) = delete;
    ~Turn() {
      if (turns_ != nullptr) turns_->release();
    }

   private:
    friend class LinkTurns;
    explicit Turn(LinkTurns* turns) : turns_(turns) {}
    LinkTurns* turns_;  // null: nested in a turn of the same thread
  };

  // Waits until the link is free and, for a routine turn, no safety turn is waiting.
  Turn take(TurnPriority priority);

  // For tests: threads waiting for a turn of each priority.
  std::size_t waiting(TurnPriority priority) const;

 private:
  void release();

  mutable std::mutex mutex_;
  std::condition_variable changed_;
  bool held_ = false;
  std::thread::id holder_;
  std::size_t routine_waiting_ = 0;
  std::size_t safety_waiting_ = 0;
};

}  // namespace wavebench::modbus
