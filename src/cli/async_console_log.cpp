#include "async_console_log.hpp"

#include <spdlog/sinks/stdout_color_sinks.h>

#include <memory>

#include "wavebench/daemon/async_logging.hpp"

namespace wavebench::cli {

AsyncConsoleLog::AsyncConsoleLog() {
  // The sink of spdlog's default logger, behind the queue.
  daemon::install_async_default_logger(
      "wavebench", {std::make_shared<spdlog::sinks::stdout_color_sink_mt>()}, spdlog::level::info);
}

AsyncConsoleLog::~AsyncConsoleLog() {
  daemon::finish_async_logging();
}

}  // namespace wavebench::cli
