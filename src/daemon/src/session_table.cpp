#include "wavebench/daemon/session_table.hpp"

#include <algorithm>

#include "wavebench/daemon/api_token.hpp"

namespace wavebench::daemon {

SessionTable::SessionTable(std::size_t capacity, std::chrono::seconds idle_timeout, Clock clock,
                           std::chrono::seconds max_age)
    : capacity_(std::max<std::size_t>(capacity, 1)),
      idle_timeout_(idle_timeout),
      max_age_(std::max(max_age, idle_timeout)),
      clock_(clock ? std::move(clock) : Clock([] { return std::chrono::steady_clock::now(); })) {}

void SessionTable::drop_expired(std::chrono::steady_clock::time_point now) {
  std::erase_if(sessions_, [&](const auto& entry) {
    return now - entry.second.last_use >= idle_timeout_ || now - entry.second.created >= max_age_;
  });
}

std::string SessionTable::create(SessionIdentity who) {
  const std::lock_guard lock(mutex_);
  const auto now = clock_();
  drop_expired(now);
  while (sessions_.size() >= capacity_) {
    const auto oldest = std::min_element(
        sessions_.begin(), sessions_.end(),
        [](const auto& a, const auto& b) { return a.second.last_use < b.second.last_use; });
    sessions_.erase(oldest);
  }
  auto id = random_hex_token();
  sessions_[id] = Entry{std::move(who), now, now};
  return id;
}

std::optional<SessionIdentity> SessionTable::use(std::string_view id) {
  if (id.size() != 64) return std::nullopt;
  const std::lock_guard lock(mutex_);
  const auto now = clock_();
  drop_expired(now);
  const auto it = sessions_.find(std::string(id));
  if (it == sessions_.end()) return std::nullopt;
  it->second.last_use = now;
  return it->second.who;
}

void SessionTable::remove(std::string_view id) {
  const std::lock_guard lock(mutex_);
  sessions_.erase(std::string(id));
}

std::size_t SessionTable::size() const {
  const std::lock_guard lock(mutex_);
  return sessions_.size();
}

}  // namespace wavebench::daemon
