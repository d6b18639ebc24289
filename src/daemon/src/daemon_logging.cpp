#include "wavebench/daemon/daemon_logging.hpp"

#include <spdlog/sinks/rotating_file_sink.h>
#include <spdlog/sinks/stdout_color_sinks.h>

#include <memory>
#include <stdexcept>

#include "wavebench/daemon/async_logging.hpp"

namespace wavebench::daemon {

void setup_daemon_logging(const std::filesystem::path& log_dir, bool verbose) {
  constexpr std::size_t kFileBytes = 5u << 20;
  constexpr std::size_t kFiles = 5;
  std::shared_ptr<spdlog::sinks::rotating_file_sink_mt> file;
  try {
    std::filesystem::create_directories(log_dir);
    file = std::make_shared<spdlog::sinks::rotating_file_sink_mt>(
        (log_dir / "wavebenchd.log").string(), kFileBytes, kFiles);
  } catch (const std::exception& e) {
    throw std::runtime_error("--log-dir " + log_dir.string() + ": cannot open the log (" +
                             e.what() + ")");
  }
  auto console = std::make_shared<spdlog::sinks::stderr_color_sink_mt>();
  install_async_default_logger("wavebenchd", {console, file},
                               verbose ? spdlog::level::debug : spdlog::level::info);
}

}  // namespace wavebench::daemon
