#include "wavebench/config/shipped_configs.hpp"

#include <cstdlib>
#include <system_error>

namespace wavebench::config {

std::filesystem::path shipped_config_dir() {
  if (const char* dir = std::getenv("WAVEBENCH_CONFIG_DIR"); dir != nullptr && *dir != 0) {
    return dir;
  }
  std::error_code ec;
  const auto exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    const auto installed = exe.parent_path().parent_path() / "share" / "wavebench" / "configs";
    if (std::filesystem::is_directory(installed, ec)) return installed;
  }
  return WAVEBENCH_SOURCE_CONFIG_DIR;
}

}  // namespace wavebench::config
