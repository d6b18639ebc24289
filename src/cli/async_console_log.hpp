#pragma once
// For the commands that drive a bench: spdlog's default logger becomes asynchronous for the
// scope (wavebench/daemon/async_logging.hpp), so a log line from the bench thread never waits
// on the terminal. The scope's end writes every queued line and reports overruns.

namespace wavebench::cli {

class AsyncConsoleLog {
 public:
  AsyncConsoleLog();
  ~AsyncConsoleLog();
  AsyncConsoleLog(const AsyncConsoleLog&) = delete;
  AsyncConsoleLog& operator=(const AsyncConsoleLog&) = delete;
};

}  // namespace wavebench::cli
