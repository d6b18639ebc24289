#include "wavebench/exports/export_folder.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>
#include <string_view>
#include <system_error>

namespace wavebench::exports {
namespace fs = std::filesystem;

namespace {

constexpr const char* kWrittenBy = "wavebench export";
constexpr std::array<std::string_view, 7> kOwnFiles{kExportMarkerFile, "samples.mat",  "samples.h5",
                                                    "samples.csv",     "samples.json", "run.json",
                                                    "results.json"};

bool own_file_name(const std::string& name) {
  for (const auto own : kOwnFiles) {
    if (name == own) return true;
  }
  return false;
}

bool has_marker(const fs::path& dir) {
  const fs::path marker = dir / kExportMarkerFile;
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

[[noreturn]] void fail(const std::string& what, const fs::path& path) {
  throw std::system_error(errno, std::generic_category(), what + " " + path.string());
}

}  // namespace

std::optional<std::string> export_folder_refusal(const fs::path& dir) {
  std::error_code ec;
  const fs::file_status status = fs::symlink_status(dir, ec);
  if (!fs::exists(status)) return std::nullopt;
  if (fs::is_symlink(status)) return "it is a symbolic link; name a folder";
  if (!fs::is_directory(status)) return "it is a file, not a folder; nothing was changed";
  if (fs::is_empty(dir, ec)) return std::nullopt;
  if (!has_marker(dir)) {
    return "the folder is not empty and was not written by wavebench export (no " +
           std::string(kExportMarkerFile) + "); name a new or empty folder";
  }
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    const std::string name = entry.path().filename().string();
    // Temporary files of an export that was killed are its own too.
    const bool temp = name.size() > 1 && name[0] == '.' && name.find(".tmp") != std::string::npos;
    if ((!own_file_name(name) && !temp) || !fs::is_regular_file(entry.symlink_status(ec))) {
      return "the folder holds '" + name +
             "', which wavebench export did not write; move it away or name another folder";
    }
  }
  if (ec) return "the folder cannot be read: " + ec.message();
  return std::nullopt;
}

void prepare_export_folder(const fs::path& dir, const std::string& run_id) {
  if (const auto refusal = export_folder_refusal(dir)) {
    throw std::runtime_error("--out " + dir.string() + ": " + *refusal);
  }
  fs::create_directories(dir);
  const nlohmann::json marker = {{"written_by", kWrittenBy}, {"format", 1}, {"run_id", run_id}};
  std::ofstream out(dir / kExportMarkerFile);
  out << marker.dump() << "\n";
  if (!out) throw std::runtime_error("cannot write " + (dir / kExportMarkerFile).string());
}

PendingFile::PendingFile(fs::path target)
    : target_(std::move(target)),
      temp_(target_.parent_path() /
            ("." + target_.filename().string() + ".tmp" + std::to_string(::getpid()))) {}

PendingFile::~PendingFile() {
  if (!committed_) ::unlink(temp_.c_str());
}

void PendingFile::commit() {
  const int fd = ::open(temp_.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) fail("export: cannot open", temp_);
  if (::fsync(fd) != 0) {
    const int e = errno;
    ::close(fd);
    errno = e;
    fail("export: fsync", temp_);
  }
  ::close(fd);
  if (::rename(temp_.c_str(), target_.c_str()) != 0) fail("export: rename to", target_);
  committed_ = true;
  const fs::path dir = target_.parent_path().empty() ? "." : target_.parent_path();
  const int dfd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dfd >= 0) {
    ::fsync(dfd);  // best effort: some filesystems refuse fsync on a directory
    ::close(dfd);
  }
}

}  // namespace wavebench::exports
