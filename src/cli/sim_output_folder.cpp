#include "sim_output_folder.hpp"

#include <signal.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>
#include <system_error>

namespace wavebench::cli {
namespace {

namespace fs = std::filesystem;

// Everything `wavebench sim` ever writes into its folder.
constexpr std::array<const char*, 8> kOwnFiles = {
    kSimMarkerFile, "timeseries.csv",     "summary.json", "time_response.png",
    "spectrum.png", "phase_portrait.png", "poincare.png", "bifurcation.png"};
constexpr const char* kWrittenBy = "wavebench sim";

bool own_file_name(const std::string& name) {
  for (const char* f : kOwnFiles) {
    if (name == f) return true;
  }
  return false;
}

bool has_marker(const fs::path& dir) {
  const fs::path marker = dir / kSimMarkerFile;
  std::error_code ec;
  if (!fs::is_regular_file(fs::symlink_status(marker, ec)) || fs::file_size(marker, ec) > 4096) {
    return false;
  }
  std::ifstream in(marker);
  std::stringstream text;
  text << in.rdbuf();
  const auto j = nlohmann::json::parse(text.str(), nullptr, false);
  return j.is_object() && j.value("written_by", "") == kWrittenBy;
}

// The first entry of `dir` a sim did not write (a folder, a link, another name), or "".
std::string first_foreign_entry(const fs::path& dir) {
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    const std::string name = entry.path().filename().string();
    if (!own_file_name(name) || !fs::is_regular_file(entry.symlink_status(ec))) return name;
  }
  if (ec) return "(unreadable: " + ec.message() + ")";
  return "";
}

}  // namespace

std::optional<std::string> sim_output_refusal(const fs::path& out) {
  std::error_code ec;
  const fs::file_status status = fs::symlink_status(out, ec);
  if (!fs::exists(status)) return std::nullopt;
  if (fs::is_symlink(status)) return "it is a symbolic link; name a folder";
  if (!fs::is_directory(status)) return "it is a file, not a folder; nothing was changed";
  if (fs::is_empty(out, ec)) return std::nullopt;
  if (!has_marker(out)) {
    return "the folder is not empty and was not written by wavebench sim (no " +
           std::string(kSimMarkerFile) + "); name a new or empty folder";
  }
  if (const std::string foreign = first_foreign_entry(out); !foreign.empty()) {
    return "the folder holds '" + foreign +
           "', which wavebench sim did not write; move it away or name another folder";
  }
  return std::nullopt;
}

void write_sim_marker(const fs::path& dir, const std::string& config) {
  const nlohmann::json marker = {{"written_by", kWrittenBy}, {"format", 1}, {"config", config}};
  std::ofstream out(dir / kSimMarkerFile);
  out << marker.dump() << "\n";
  if (!out) throw std::runtime_error("cannot write " + (dir / kSimMarkerFile).string());
}

void remove_sim_output(const fs::path& dir) noexcept {
  std::error_code ec;
  for (const char* f : kOwnFiles) fs::remove(dir / f, ec);
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
    if (!has_marker(entry.path()) || !first_foreign_entry(entry.path()).empty()) continue;
    remove_sim_output(entry.path());
  }
}

}  // namespace wavebench::cli
