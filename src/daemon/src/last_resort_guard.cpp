#include "wavebench/daemon/last_resort_guard.hpp"

#include <atomic>
#include <cstdlib>
#include <exception>
#include <mutex>

namespace wavebench::daemon {

namespace {

std::mutex guard_mutex;
std::function<void(const std::string&)> guard_action;
std::atomic<bool> fired{false};

std::string what_escaped() {
  const auto current = std::current_exception();
  if (!current) return "std::terminate without an exception";
  try {
    std::rethrow_exception(current);
  } catch (const std::exception& e) {
    return std::string("uncaught exception: ") + e.what();
  } catch (...) {
    return "uncaught exception of unknown type";
  }
}

[[noreturn]] void on_terminate() noexcept {
  if (!fired.exchange(true)) {
    std::function<void(const std::string&)> action;
    {
      std::lock_guard lock(guard_mutex);
      action = guard_action;
    }
    if (action) {
      try {
        action(what_escaped());
      } catch (...) {
      }
    }
  }
  std::abort();
}

}  // namespace

void install_last_resort_guard(std::function<void(const std::string&)> on_terminate_action) {
  {
    std::lock_guard lock(guard_mutex);
    guard_action = std::move(on_terminate_action);
  }
  std::set_terminate(on_terminate);
}

void remove_last_resort_guard() {
  std::lock_guard lock(guard_mutex);
  guard_action = nullptr;
}

}  // namespace wavebench::daemon
