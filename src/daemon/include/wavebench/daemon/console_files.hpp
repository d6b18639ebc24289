#pragma once
// The operator console's files (web/, copied into <build>/web by the build or installed under
// share/wavebench/web), served read-only by the daemon so that the console needs no network.
// Only GET/HEAD of names made of [A-Za-z0-9._-] segments that do not start with '.', only
// regular files inside the root (a symlink out of it is refused), at most kMaxFileBytes, and
// only the content types of kContentTypes: anything else is 404.

#include <cstdint>
#include <filesystem>
#include <optional>

#include "wavebench/daemon/daemon_api.hpp"
#include "wavebench/daemon/http_target.hpp"

namespace wavebench::daemon {

class ConsoleFiles {
 public:
  static constexpr std::uintmax_t kMaxFileBytes = 8u << 20;

  ConsoleFiles() = default;  // no console: every page answers 404 saying so
  explicit ConsoleFiles(std::filesystem::path root);

  // "/" is index.html; "/history" is history.html (a last segment without a dot gets .html).
  ApiResponse answer(const HttpTarget& target) const;
  bool enabled() const { return !root_.empty(); }
  const std::filesystem::path& root() const { return root_; }

 private:
  std::filesystem::path root_;  // canonical
};

// Where the console is when --web-root is not given: $WAVEBENCH_WEB_DIR, else
// <executable>/../share/wavebench/web (an install), else the build tree's web/ folder.
// Empty when none exists.
std::filesystem::path default_console_root();

}  // namespace wavebench::daemon
