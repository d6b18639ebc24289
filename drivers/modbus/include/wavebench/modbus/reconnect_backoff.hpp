#pragma once
// When to try a lost link again: the wait doubles after each failed attempt, up to a ceiling,
// so a dead controller is not hammered and a recovered one is found quickly.

#include <algorithm>
#include <chrono>

namespace wavebench::modbus {

class ReconnectBackoff {
 public:
  using Clock = std::chrono::steady_clock;

  ReconnectBackoff(std::chrono::milliseconds initial, std::chrono::milliseconds max)
      : initial_(initial), max_(max), delay_(initial) {}

  bool due(Clock::time_point now) const { return now >= next_attempt_; }
  void failed(Clock::time_point now) {
    next_attempt_ = now + delay_;
    delay_ = std::min(delay_ * 2, max_);
    ++failures_;
  }
  void succeeded() {
    delay_ = initial_;
    next_attempt_ = {};
    failures_ = 0;
  }
  std::chrono::milliseconds current_delay() const { return delay_; }
  Clock::time_point next_attempt() const { return next_attempt_; }
  int failures() const { return failures_; }

 private:
  std::chrono::milliseconds initial_;
  std::chrono::milliseconds max_;
  std::chrono::milliseconds delay_;
  Clock::time_point next_attempt_{};
  int failures_ = 0;
};

}  // namespace wavebench::modbus
