#pragma once
// The process's last resort: when std::terminate is reached (an exception nothing caught, a
// noexcept violated), `on_terminate` runs once — the daemon puts the bench in its safe state
// and marks the active run — before the process aborts.

#include <functional>
#include <string>

namespace wavebench::daemon {

// `on_terminate` receives a short description of what escaped. Replaces an earlier guard.
void install_last_resort_guard(std::function<void(const std::string&)> on_terminate);
void remove_last_resort_guard();

}  // namespace wavebench::daemon
