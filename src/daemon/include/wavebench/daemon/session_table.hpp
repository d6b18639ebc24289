#pragma once
// Browser sessions of the console (issues #10, #21): the login page trades an account's name
// and password (or the daemon's token) for a random session id sent back as an HttpOnly
// cookie. A session remembers who logged in and their role. It expires when unused for its
// idle timeout (the open console asks GET /api/session every minute, which renews it) and in
// any case at its absolute cap after creation. The table is bounded: past its capacity the
// least recently used session goes. An expired session never locks anyone out of the stop
// (daemon_api.hpp: the console's stop needs no session).

#include <chrono>
#include <cstddef>
#include <functional>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>

#include "wavebench/daemon/accounts.hpp"

namespace wavebench::daemon {

// Who a session belongs to: an account, or the token (account empty, acts as an engineer).
struct SessionIdentity {
  std::string account;
  Role role = Role::kEngineer;
};

class SessionTable {
 public:
  using Clock = std::function<std::chrono::steady_clock::time_point()>;
  static constexpr std::size_t kDefaultCapacity = 64;
  static constexpr std::chrono::seconds kDefaultIdleTimeout{30 * 60};
  static constexpr std::chrono::seconds kDefaultMaxAge{12 * 3600};

  explicit SessionTable(std::size_t capacity = kDefaultCapacity,
                        std::chrono::seconds idle_timeout = kDefaultIdleTimeout,
                        Clock clock = nullptr, std::chrono::seconds max_age = kDefaultMaxAge);

  // A new session: 256 random bits as 64 hex digits. Evicts the least recently used one when
  // the table is full.
  std::string create(SessionIdentity who = {});
  // Who `id` belongs to when it is a live session; renews it. Looked up by hash: with 256
  // random bits there is no prefix to guess from timing, unlike a byte-wise compare.
  std::optional<SessionIdentity> use(std::string_view id);
  void remove(std::string_view id);
  std::size_t size() const;
  std::chrono::seconds lifetime() const { return idle_timeout_; }
  std::chrono::seconds max_age() const { return max_age_; }

 private:
  struct Entry {
    SessionIdentity who;
    std::chrono::steady_clock::time_point created;
    std::chrono::steady_clock::time_point last_use;
  };
  void drop_expired(std::chrono::steady_clock::time_point now);

  std::size_t capacity_;
  std::chrono::seconds idle_timeout_;
  std::chrono::seconds max_age_;
  Clock clock_;
  mutable std::mutex mutex_;  // shared only among API threads
  std::unordered_map<std::string, Entry> sessions_;
};

}  // namespace wavebench::daemon
