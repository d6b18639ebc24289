#include "wavebench/exports/export_scratch.hpp"

#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <string_view>

#include "wavebench/exports/export_format.hpp"

namespace wavebench::exports {

namespace fs = std::filesystem;

namespace {

bool digits(std::string_view s) {
  return !s.empty() && s.size() <= 10 && s.find_first_not_of("0123456789") == std::string::npos;
}

// The pid of "wavebench-export-<pid>-<n>", or 0 for any other name.
pid_t scratch_pid(const std::string& name) {
  const std::string_view prefix = kExportScratchPrefix;
  if (name.size() <= prefix.size() || name.compare(0, prefix.size(), prefix) != 0) return 0;
  const std::string_view rest = std::string_view(name).substr(prefix.size());
  const auto dash = rest.find('-');
  if (dash == std::string_view::npos || !digits(rest.substr(0, dash)) ||
      !digits(rest.substr(dash + 1))) {
    return 0;
  }
  const long pid = std::stol(std::string(rest.substr(0, dash)));
  return pid > 0 && pid < (1L << 30) ? static_cast<pid_t>(pid) : 0;
}

// samples.<format> or the hidden temporary beside it (".samples.h5.tmp<pid>").
bool export_file_name(const std::string& name) {
  for (const auto format :
       {ExportFormat::kMat, ExportFormat::kHdf5, ExportFormat::kCsv, ExportFormat::kJson}) {
    const std::string file = samples_file_name(format);
    if (name == file) return true;
    const std::string temp = "." + file + ".tmp";
    if (name.compare(0, temp.size(), temp) == 0 &&
        digits(std::string_view(name).substr(temp.size())))
      return true;
  }
  return false;
}

bool only_export_files(const fs::path& dir) {
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    if (!export_file_name(entry.path().filename().string()) ||
        !fs::is_regular_file(entry.symlink_status(ec))) {
      return false;
    }
  }
  return !ec;
}

}  // namespace

std::string export_scratch_name(unsigned sequence) {
  return kExportScratchPrefix + std::to_string(::getpid()) + "-" + std::to_string(sequence);
}

std::size_t remove_stale_export_scratch(const fs::path& parent) {
  std::size_t removed = 0;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(parent, ec)) {
    const std::string name = entry.path().filename().string();
    const pid_t pid = scratch_pid(name);
    if (pid == 0 || pid == ::getpid()) continue;
    struct stat st {};
    if (::lstat(entry.path().c_str(), &st) != 0 || !S_ISDIR(st.st_mode) || st.st_uid != ::geteuid())
      continue;
    if (::kill(pid, 0) == 0 || errno != ESRCH) continue;  // its process lives (or is not ours)
    if (!only_export_files(entry.path())) continue;
    std::error_code rm;
    if (fs::remove_all(entry.path(), rm) > 0 && !rm) ++removed;
  }
  return removed;
}

std::size_t remove_stale_export_scratch() {
  std::error_code ec;
  const auto temp = fs::temp_directory_path(ec);
  return ec ? 0 : remove_stale_export_scratch(temp);
}

}  // namespace wavebench::exports
