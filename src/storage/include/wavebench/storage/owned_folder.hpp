#pragma once
// A folder a wavebench command writes its output into (`wavebench sim --out`, `wavebench
// export --out`): a new folder, an empty one, or one the same command wrote before, recognised
// by its marker file and holding nothing but that command's files. Anything else is the
// user's and is never touched.

#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <span>
#include <string>
#include <string_view>

namespace wavebench::storage {

struct FolderOwner {
  std::string_view marker_file;                 // ".wavebench-sim"
  std::string_view written_by;                  // "wavebench sim", in the marker and in messages
  std::span<const std::string_view> own_files;  // the marker is one of them
  // Hidden "*.tmp*" files (PendingFile-style temporaries of a killed writer) count as its own.
  bool own_temporaries = false;
};

// The marker is there, small, and names `owner`.
bool has_owner_marker(const std::filesystem::path& dir, const FolderOwner& owner);

// The first entry of `dir` the owner did not write (a folder, a link, another name), or "".
std::string first_foreign_entry(const std::filesystem::path& dir, const FolderOwner& owner);

// Why `dir` may not receive the owner's output, or nothing when it may.
std::optional<std::string> owned_folder_refusal(const std::filesystem::path& dir,
                                                const FolderOwner& owner);

// The marker's fields ({"written_by": ..., "run_id": ...}); null when absent or unreadable.
nlohmann::json read_owner_marker(const std::filesystem::path& dir, const FolderOwner& owner);

// Removes the temporaries a killed writer of `owner` left in `dir`: ".<own file>.tmp<pid>"
// whose process is gone (the names PendingFile and write_file_atomically use). Nothing else is
// touched. Returns how many were removed.
std::size_t remove_stale_temporaries(const std::filesystem::path& dir, const FolderOwner& owner);

// Writes the marker: {"written_by": ..., "format": 1} and `fields`. Throws std::runtime_error
// naming the file.
void write_owner_marker(const std::filesystem::path& dir, const FolderOwner& owner,
                        const nlohmann::json& fields);

}  // namespace wavebench::storage
