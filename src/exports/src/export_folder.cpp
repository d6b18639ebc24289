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

#include "wavebench/storage/owned_folder.hpp"

namespace wavebench::exports {
namespace fs = std::filesystem;

namespace {

constexpr std::array<std::string_view, 7> kOwnFiles{kExportMarkerFile, "samples.mat",  "samples.h5",
                                                    "samples.csv",     "samples.json", "run.json",
                                                    "results.json"};
// Temporary files of an export that was killed are its own too.
constexpr storage::FolderOwner kOwner{kExportMarkerFile, "wavebench export", kOwnFiles, true};

[[noreturn]] void fail(const std::string& what, const fs::path& path) {
  throw std::system_error(errno, std::generic_category(), what + " " + path.string());
}

}  // namespace

std::optional<std::string> export_folder_refusal(const fs::path& dir, const std::string& run_id) {
  if (auto refusal = storage::owned_folder_refusal(dir, kOwner)) return refusal;
  const auto marker = storage::read_owner_marker(dir, kOwner);
  if (marker.is_object()) {
    const auto* held = marker.contains("run_id") && marker["run_id"].is_string()
                           ? marker["run_id"].get_ptr<const std::string*>()
                           : nullptr;
    if (!held || *held != run_id) {
      return "the folder holds the export of run '" + (held ? *held : std::string("?")) +
             "', not of run '" + run_id +
             "'; an export folder holds one run's export: name a new or empty folder";
    }
  }
  return std::nullopt;
}

bool prepare_export_folder(const fs::path& dir, const std::string& run_id) {
  if (const auto refusal = export_folder_refusal(dir, run_id)) {
    throw std::runtime_error("--out " + dir.string() + ": " + *refusal);
  }
  std::error_code ec;
  const bool bare = !fs::exists(dir, ec) || fs::is_empty(dir, ec);
  fs::create_directories(dir);
  storage::remove_stale_temporaries(dir, kOwner);
  storage::write_owner_marker(dir, kOwner, {{"run_id", run_id}});
  return bare;
}

void remove_export_folder_if_bare(const fs::path& dir) {
  std::error_code ec;
  if (storage::first_foreign_entry(dir, kOwner).empty()) {
    for (const auto& entry : fs::directory_iterator(dir, ec)) {
      if (entry.path().filename() != kExportMarkerFile) return;
    }
    fs::remove(dir / kExportMarkerFile, ec);
    fs::remove(dir, ec);
  }
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
