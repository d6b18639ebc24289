#pragma once
// Browser sessions of the console (issue #10): the login page trades the daemon's token for a
// random session id sent back as an HttpOnly cookie. The table is bounded: past its capacity
// the least recently used session goes; a session unused for its lifetime expires. Each use
// renews it, so an open console (it asks GET /api/session every minute) keeps its session and
// the operator is never locked out of the stop button by an expiry.

#include <chrono>
#include <cstddef>
#include <functional>
#include <mutex>
#include <string>
#include <string_view>
#include <unordered_map>

namespace wavebench::daemon {

class SessionTable {
 public:
  using Clock = std::function<std::chrono::steady_clock::time_point()>;
  static constexpr std::size_t kDefaultCapacity = 64;
  static constexpr std::chrono::seconds kDefaultLifetime{12 * 3600};

  explicit SessionTable(std::size_t capacity = kDefaultCapacity,
                        std::chrono::seconds lifetime = kDefaultLifetime, Clock clock = nullptr);

  // A new session: 256 random bits as 64 hex digits. Evicts the least recently used one when
  // the table is full.
  std::string create();
  // Whether `id` is a live session; renews it when it is. Looked up by hash: with 256 random
  // bits there is no prefix to guess from timing, unlike a byte-wise compare of a fixed secret.
  bool use(std::string_view id);
  void remove(std::string_view id);
  std::size_t size() const;
  std::chrono::seconds lifetime() const { return lifetime_; }

 private:
  void drop_expired(std::chrono::steady_clock::time_point now);

  std::size_t capacity_;
  std::chrono::seconds lifetime_;
  Clock clock_;
  mutable std::mutex mutex_;  // shared only among API threads
  std::unordered_map<std::string, std::chrono::steady_clock::time_point> last_use_;
};

}  // namespace wavebench::daemon
