#include "wavebench/daemon/session_table.hpp"

#include <algorithm>

#include "wavebench/daemon/api_token.hpp"

namespace wavebench::daemon {

SessionTable::SessionTable(std::size_t capacity, std::chrono::seconds lifetime, Clock clock)
    : capacity_(std::max<std::size_t>(capacity, 1)),
      lifetime_(lifetime),
      clock_(clock ? std::move(clock) : Clock([] { return std::chrono::steady_clock::now(); })) {}

void SessionTable::drop_expired(std::chrono::steady_clock::time_point now) {
  std::erase_if(last_use_, [&](const auto& entry) { return now - entry.second >= lifetime_; });
}

std::string SessionTable::create() {
  const std::lock_guard lock(mutex_);
  const auto now = clock_();
  drop_expired(now);
  while (last_use_.size() >= capacity_) {
    const auto oldest =
        std::min_element(last_use_.begin(), last_use_.end(),
                         [](const auto& a, const auto& b) { return a.second < b.second; });
    last_use_.erase(oldest);
  }
  auto id = random_hex_token();
  last_use_[id] = now;
  return id;
}

bool SessionTable::use(std::string_view id) {
  if (id.size() != 64) return false;
  const std::lock_guard lock(mutex_);
  const auto now = clock_();
  drop_expired(now);
  const auto it = last_use_.find(std::string(id));
  if (it == last_use_.end()) return false;
  it->second = now;
  return true;
}

void SessionTable::remove(std::string_view id) {
  const std::lock_guard lock(mutex_);
  last_use_.erase(std::string(id));
}

std::size_t SessionTable::size() const {
  const std::lock_guard lock(mutex_);
  return last_use_.size();
}

}  // namespace wavebench::daemon
