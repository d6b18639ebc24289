#include "wavebench/daemon/async_logging.hpp"

#include <spdlog/async.h>
#include <spdlog/spdlog.h>

#include <memory>

namespace wavebench::daemon {

namespace {
constexpr std::size_t kQueuedLines = 8192;
}  // namespace

void install_async_default_logger(const std::string& name, spdlog::sinks_init_list sinks,
                                  spdlog::level::level_enum level) {
  spdlog::init_thread_pool(kQueuedLines, 1);
  auto logger = std::make_shared<spdlog::async_logger>(
      name, sinks, spdlog::thread_pool(), spdlog::async_overflow_policy::overrun_oldest);
  logger->set_level(level);
  logger->flush_on(spdlog::level::info);  // on the worker thread
  spdlog::set_default_logger(logger);
}

std::size_t log_lines_dropped() {
  const auto pool = spdlog::thread_pool();
  return pool ? pool->overrun_counter() : 0;
}

void finish_async_logging() noexcept {
  try {
    const auto pool = spdlog::thread_pool();
    if (!pool) return;
    const std::size_t dropped = pool->overrun_counter();
    if (dropped > 0) spdlog::warn("{} log lines dropped: the log queue was full", dropped);
    const auto async = spdlog::default_logger();
    auto sync = std::make_shared<spdlog::logger>(async->name(), async->sinks().begin(),
                                                 async->sinks().end());
    sync->set_level(async->level());
    sync->flush_on(spdlog::level::info);
    spdlog::set_default_logger(sync);
    // The registry held the last reference to the pool: its destructor lets the worker write
    // every queued line, then joins it.
    spdlog::details::registry::instance().set_tp(nullptr);
  } catch (...) {  // NOLINT(bugprone-empty-catch): nowhere left to report a failing log
  }
}

}  // namespace wavebench::daemon
