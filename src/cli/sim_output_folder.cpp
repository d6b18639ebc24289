#include "sim_output_folder.hpp"

#include <signal.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>
#include <string_view>
#include <system_error>

#include "wavebench/storage/owned_folder.hpp"

namespace wavebench::cli {
namespace {

namespace fs = std::filesystem;

// Everything `wavebench sim` ever writes into its folder.
constexpr std::array<std::string_view, 8> kOwnFiles = {
    kSimMarkerFile, "timeseries.csv",     "summary.json", "time_response.png",
    "spectrum.png", "phase_portrait.png", "poincare.png", "bifurcation.png"};
constexpr storage::FolderOwner kOwner{kSimMarkerFile, "wavebench sim", kOwnFiles};

}  // namespace

std::optional<std::string> sim_output_refusal(const fs::path& out) {
  return storage::owned_folder_refusal(out, kOwner);
}

void write_sim_marker(const fs::path& dir, const std::string& config) {
  storage::write_owner_marker(dir, kOwner, {{"config", config}});
}

void remove_sim_output(const fs::path& dir) noexcept {
  std::error_code ec;
  for (const auto f : kOwnFiles) fs::remove(dir / f, ec);
  fs::remove(dir, ec);  // only succeeds once the folder is empty
}

void move_sim_output_into_place(const fs::path& tmp, const fs::path& out) {
  if (const auto refusal = sim_output_refusal(out)) {
    throw std::runtime_error(out.string() + ": " + *refusal);
  }
  std::error_code ec;
  if (!fs::exists(fs::symlink_status(out, ec)) || fs::is_empty(out, ec)) {
    fs::rename(tmp, out);  // rename(2) replaces an empty folder
    return;
  }
  const fs::path old =
      out.parent_path() / ("." + out.filename().string() + ".old-" + std::to_string(::getpid()));
  fs::rename(out, old);
  try {
    fs::rename(tmp, out);
  } catch (...) {
    fs::rename(old, out);
    throw;
  }
  remove_sim_output(old);
}

fs::path sim_temp_folder(const fs::path& out) {
  return out.parent_path() / ("." + out.filename().string() + ".tmp-" + std::to_string(::getpid()));
}

void remove_stale_sim_temp_folders(const fs::path& out) noexcept {
  const std::string prefix = "." + out.filename().string() + ".tmp-";
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(out.parent_path(), ec)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind(prefix, 0) != 0 || !entry.is_directory(ec) || entry.is_symlink(ec)) continue;
    const std::string pid_text = name.substr(prefix.size());
    if (pid_text.empty() || pid_text.find_first_not_of("0123456789") != std::string::npos ||
        pid_text.size() > 9) {
      continue;
    }
    const pid_t pid = static_cast<pid_t>(std::stol(pid_text));
    if (pid == ::getpid() || ::kill(pid, 0) == 0 || errno != ESRCH) continue;  // alive
    if (!storage::has_owner_marker(entry.path(), kOwner) ||
        !storage::first_foreign_entry(entry.path(), kOwner).empty()) {
      continue;
    }
    remove_sim_output(entry.path());
  }
}

}  // namespace wavebench::cli
