#pragma once
// Failed logins, counted per key (an account name, a client address): after kFreeFailures in a
// row, each further attempt under that key must wait a lockout that doubles with every failure
// (1 s, 2 s, 4 s, ... up to kMaxLockout); an attempt inside the lockout is refused at once (429
// with Retry-After) without checking the password, so guessing costs time, not just CPU. A
// success clears the key. Bounded: past kMaxKeys the oldest key goes.

#include <chrono>
#include <cstddef>
#include <functional>
#include <map>
#include <mutex>
#include <string>

namespace wavebench::daemon {

class LoginThrottle {
 public:
  using Clock = std::function<std::chrono::steady_clock::time_point()>;
  static constexpr int kFreeFailures = 5;
  static constexpr std::chrono::seconds kMaxLockout{15 * 60};
  static constexpr std::size_t kMaxKeys = 4096;

  explicit LoginThrottle(Clock clock = nullptr);
  // How long `key` must still wait; zero when an attempt may go ahead now.
  std::chrono::seconds wait(const std::string& key) const;
  void failed(const std::string& key);
  void succeeded(const std::string& key);

 private:
  struct Failures {
    int count = 0;
    std::chrono::steady_clock::time_point last;
    std::chrono::steady_clock::time_point until;
  };
  Clock clock_;
  mutable std::mutex mutex_;
  std::map<std::string, Failures> failures_;
};

}  // namespace wavebench::daemon
