#pragma once
// Scratch folders of the daemon's export downloads: <temp>/wavebench-export-<pid>-<n>, removed
// with their files when the download is answered. A daemon that was killed leaves them (and
// the hidden temporary file of an export cut off half way, tens of MB); the next start removes
// them: only folders with this name, of a process that is gone, owned by this user, holding
// nothing but an export's files.

#include <cstddef>
#include <filesystem>
#include <string>

namespace wavebench::exports {

inline constexpr const char* kExportScratchPrefix = "wavebench-export-";

// "wavebench-export-<pid>-<n>": the name a scratch folder of this process takes.
std::string export_scratch_name(unsigned sequence);

// Removes the stale scratch folders in `parent` (default: the system's temporary folder).
// Returns how many were removed; never throws.
std::size_t remove_stale_export_scratch(const std::filesystem::path& parent);
std::size_t remove_stale_export_scratch();

}  // namespace wavebench::exports
