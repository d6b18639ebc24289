#pragma once
// spdlog's default logger written by spdlog's worker thread from a bounded queue (issue #9):
// a log line from the bench thread never waits on the disk or the terminal. A full queue
// overruns its oldest line (spdlog 1.10 has no discard-newest; neither waits) and the pool
// counts the overruns. For wavebenchd and the `wavebench` commands that drive a bench.

#include <spdlog/common.h>

#include <cstddef>
#include <string>

namespace wavebench::daemon {

void install_async_default_logger(const std::string& name, spdlog::sinks_init_list sinks,
                                  spdlog::level::level_enum level);

// Lines lost to a full queue since the start.
std::size_t log_lines_dropped();

// Normal exit and the last resort: reports overruns, writes every queued line and stops the
// worker; the default logger goes on synchronously with the same sinks, so that a line logged
// afterwards (e.g. by the safe-state path) is still written. Idempotent.
void finish_async_logging() noexcept;

}  // namespace wavebench::daemon
