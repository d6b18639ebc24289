#pragma once
// SIGINT, SIGTERM and SIGHUP while a command writes files: the handler only records the signal
// (async-signal-safe); the main thread notices at its next check, removes what it half wrote
// and then dies of the same signal, so callers still see "killed by SIGTERM".

#include <csignal>
#include <stdexcept>

namespace wavebench::cli {

class StopRequested : public std::runtime_error {
 public:
  StopRequested() : std::runtime_error("stopped by a signal") {}
};

class StopSignals {
 public:
  StopSignals();   // installs the handlers
  ~StopSignals();  // restores the previous ones
  StopSignals(const StopSignals&) = delete;
  StopSignals& operator=(const StopSignals&) = delete;

  static bool requested() noexcept;
  static void throw_if_requested();  // throws StopRequested
  // Restores the default action and raises the recorded signal again.
  [[noreturn]] void reraise() noexcept;

 private:
  struct sigaction old_int_ {
  }, old_term_{}, old_hup_{};
};

}  // namespace wavebench::cli
