#include "stop_signals.hpp"

#include <cstdlib>

namespace wavebench::cli {
namespace {

volatile std::sig_atomic_t g_signal = 0;

extern "C" void record_signal(int sig) {
  g_signal = sig;
}

}  // namespace

StopSignals::StopSignals() {
  g_signal = 0;
  struct sigaction sa {};
  sa.sa_handler = record_signal;
  sigemptyset(&sa.sa_mask);
  sigaction(SIGINT, &sa, &old_int_);
  sigaction(SIGTERM, &sa, &old_term_);
  sigaction(SIGHUP, &sa, &old_hup_);
}

StopSignals::~StopSignals() {
  sigaction(SIGINT, &old_int_, nullptr);
  sigaction(SIGTERM, &old_term_, nullptr);
  sigaction(SIGHUP, &old_hup_, nullptr);
}

bool StopSignals::requested() noexcept {
  return g_signal != 0;
}

void StopSignals::throw_if_requested() {
  if (requested()) throw StopRequested();
}

void StopSignals::reraise() noexcept {
  const int sig = g_signal != 0 ? static_cast<int>(g_signal) : SIGTERM;
  struct sigaction dfl {};
  dfl.sa_handler = SIG_DFL;
  sigemptyset(&dfl.sa_mask);
  sigaction(sig, &dfl, nullptr);
  std::raise(sig);
  std::_Exit(128 + sig);  // the signal was blocked or ignored by the parent
}

}  // namespace wavebench::cli
