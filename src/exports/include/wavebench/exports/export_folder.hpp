#pragma once
// Where `wavebench export --out DIR` may write: a new folder, an empty one, or one an export
// wrote before (its marker file, and nothing but an export's files). Anything else is the
// user's and is never touched. Files go in whole: written beside their name, synced, renamed.

#include <filesystem>
#include <optional>
#include <string>

namespace wavebench::exports {

inline constexpr const char* kExportMarkerFile = ".wavebench-export";

// Why `dir` may not receive run `run_id`'s export, or nothing when it may. An export folder
// holds one run's export: one that holds another run's is refused (its files are left).
std::optional<std::string> export_folder_refusal(const std::filesystem::path& dir,
                                                 const std::string& run_id);

// Creates `dir` (and its parents), removes the temporaries of killed exports in it and writes
// the marker naming the run. Throws std::runtime_error when export_folder_refusal() refuses
// it. Returns whether the folder was new or empty (an export that fails then removes it).
bool prepare_export_folder(const std::filesystem::path& dir, const std::string& run_id);

// Removes the marker and `dir` itself when nothing else is in it (a failed first export).
void remove_export_folder_if_bare(const std::filesystem::path& dir);

// A file being written under a temporary name beside `target`; removed unless commit() ran.
class PendingFile {
 public:
  explicit PendingFile(std::filesystem::path target);
  ~PendingFile();
  PendingFile(const PendingFile&) = delete;
  PendingFile& operator=(const PendingFile&) = delete;

  const std::filesystem::path& temp() const { return temp_; }
  const std::filesystem::path& target() const { return target_; }
  // fsync the temporary file, rename it over the target, fsync the folder. Throws
  // std::system_error naming the path.
  void commit();

 private:
  std::filesystem::path target_, temp_;
  bool committed_ = false;
};

}  // namespace wavebench::exports
