#pragma once
// wavebenchd's log: the console and a rotating file (wavebenchd.log, 5 MiB x 5) in log_dir,
// asynchronous (async_logging.hpp: finish_async_logging() at exit).

#include <filesystem>

namespace wavebench::daemon {

// Makes the combined logger spdlog's default. Throws std::runtime_error naming the directory
// when the file cannot be opened.
void setup_daemon_logging(const std::filesystem::path& log_dir, bool verbose);

}  // namespace wavebench::daemon
