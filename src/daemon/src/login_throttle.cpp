#include "wavebench/daemon/login_throttle.hpp"

#include <algorithm>

namespace wavebench::daemon {

LoginThrottle::LoginThrottle(Clock clock)
    : clock_(clock ? std::move(clock) : Clock([] { return std::chrono::steady_clock::now(); })) {}

std::chrono::seconds LoginThrottle::wait(const std::string& key) const {
  const std::lock_guard lock(mutex_);
  const auto it = failures_.find(key);
  if (it == failures_.end()) return std::chrono::seconds(0);
  const auto now = clock_();
  if (now >= it->second.until) return std::chrono::seconds(0);
  // Rounded up: a client that waits Retry-After seconds is let in.
  return std::chrono::ceil<std::chrono::seconds>(it->second.until - now);
}

void LoginThrottle::failed(const std::string& key) {
  const std::lock_guard lock(mutex_);
  const auto now = clock_();
  if (failures_.size() >= kMaxKeys && !failures_.contains(key)) {
    failures_.erase(std::min_element(
        failures_.begin(), failures_.end(),
        [](const auto& a, const auto& b) { return a.second.last < b.second.last; }));
  }
  auto& f = failures_[key];
  ++f.count;
  f.last = now;
  if (f.count >= kFreeFailures) {
    const int doublings = std::min(f.count - kFreeFailures, 20);
    const auto lockout =
        std::min<std::chrono::seconds>(std::chrono::seconds(1LL << doublings), kMaxLockout);
    f.until = now + lockout;
  }
}

void LoginThrottle::succeeded(const std::string& key) {
  const std::lock_guard lock(mutex_);
  failures_.erase(key);
}

}  // namespace wavebench::daemon
