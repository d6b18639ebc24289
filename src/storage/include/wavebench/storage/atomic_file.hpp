#pragma once
// Whole-file replacement that a crash never leaves half-written: temp file in the same
// directory, fsync, rename over the target, fsync the directory.

#include <filesystem>
#include <string_view>

namespace wavebench::storage {

// Throws std::system_error naming the path.
void write_file_atomically(const std::filesystem::path& path, std::string_view content);

}  // namespace wavebench::storage
