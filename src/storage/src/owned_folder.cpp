#include "wavebench/storage/owned_folder.hpp"

#include <signal.h>

#include <cerrno>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace wavebench::storage {
namespace fs = std::filesystem;

namespace {

bool own_file_name(const std::string& name, const FolderOwner& owner) {
  for (const auto own : owner.own_files) {
    if (name == own) return true;
  }
  return owner.own_temporaries && name.size() > 1 && name[0] == '.' &&
         name.find(".tmp") != std::string::npos;
}

}  // namespace

nlohmann::json read_owner_marker(const fs::path& dir, const FolderOwner& owner) {
  const fs::path marker = dir / owner.marker_file;
  std::error_code ec;
  if (!fs::is_regular_file(fs::symlink_status(marker, ec)) || fs::file_size(marker, ec) > 4096) {
    return nullptr;
  }
  std::ifstream in(marker);
  std::stringstream text;
  text << in.rdbuf();
  auto j = nlohmann::json::parse(text.str(), nullptr, false);
  if (!j.is_object() || j.value("written_by", "") != owner.written_by) return nullptr;
  return j;
}

bool has_owner_marker(const fs::path& dir, const FolderOwner& owner) {
  return !read_owner_marker(dir, owner).is_null();
}

std::size_t remove_stale_temporaries(const fs::path& dir, const FolderOwner& owner) {
  std::size_t removed = 0;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    const std::string name = entry.path().filename().string();
    for (const auto own : owner.own_files) {
      const std::string prefix = "." + std::string(own) + ".tmp";
      if (name.size() <= prefix.size() || name.compare(0, prefix.size(), prefix) != 0) continue;
      const std::string pid_text = name.substr(prefix.size());
      if (pid_text.size() > 9 || pid_text.find_first_not_of("0123456789") != std::string::npos) {
        continue;
      }
      const auto pid = static_cast<pid_t>(std::stol(pid_text));
      // A live writer's (another export into this folder right now) is left alone.
      const bool gone = pid > 0 && ::kill(pid, 0) != 0 && errno == ESRCH;
      std::error_code rm;
      if (gone && fs::is_regular_file(entry.symlink_status(rm)) && fs::remove(entry.path(), rm)) {
        ++removed;
      }
    }
  }
  return removed;
}

std::string first_foreign_entry(const fs::path& dir, const FolderOwner& owner) {
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    const std::string name = entry.path().filename().string();
    if (!own_file_name(name, owner) || !fs::is_regular_file(entry.symlink_status(ec))) {
      return name;
    }
  }
  if (ec) return "(unreadable: " + ec.message() + ")";
  return "";
}

std::optional<std::string> owned_folder_refusal(const fs::path& dir, const FolderOwner& owner) {
  std::error_code ec;
  const fs::file_status status = fs::symlink_status(dir, ec);
  if (!fs::exists(status)) return std::nullopt;
  if (fs::is_symlink(status)) return "it is a symbolic link; name a folder";
  if (!fs::is_directory(status)) return "it is a file, not a folder; nothing was changed";
  if (fs::is_empty(dir, ec)) return std::nullopt;
  const std::string by(owner.written_by);
  if (!has_owner_marker(dir, owner)) {
    return "the folder is not empty and was not written by " + by + " (no " +
           std::string(owner.marker_file) + "); name a new or empty folder";
  }
  if (const std::string foreign = first_foreign_entry(dir, owner); !foreign.empty()) {
    return "the folder holds '" + foreign + "', which " + by +
           " did not write; move it away or name another folder";
  }
  return std::nullopt;
}

void write_owner_marker(const fs::path& dir, const FolderOwner& owner,
                        const nlohmann::json& fields) {
  nlohmann::json marker = {{"written_by", owner.written_by}, {"format", 1}};
  for (const auto& [key, value] : fields.items()) marker[key] = value;
  const fs::path file = dir / owner.marker_file;
  std::ofstream out(file);
  out << marker.dump() << "\n";
  if (!out) throw std::runtime_error("cannot write " + file.string());
}

}  // namespace wavebench::storage
