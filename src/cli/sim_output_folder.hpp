#pragma once
// Where `wavebench sim --out DIR` may write: a new folder, an empty one, or one it wrote before
// (recognised by its marker file and holding nothing but its own outputs). Anything else is the
// user's and is never touched.

#include <filesystem>
#include <optional>
#include <string>

namespace wavebench::cli {

inline constexpr const char* kSimMarkerFile = ".wavebench-sim";

// Why `out` may not receive a sim's output, or nothing when it may.
std::optional<std::string> sim_output_refusal(const std::filesystem::path& out);

// Writes the marker into a folder being filled with a sim's output.
void write_sim_marker(const std::filesystem::path& dir, const std::string& config);

// Puts the finished `tmp` where `out` is. An earlier output at `out` is replaced; only its
// own files are deleted, and its folder only once it is empty. Throws when `out` changed into
// something sim_output_refusal() refuses since it was checked.
void move_sim_output_into_place(const std::filesystem::path& tmp, const std::filesystem::path& out);

// Deletes a sim's temporary folder: its own files, then the folder if that left it empty.
void remove_sim_output(const std::filesystem::path& dir) noexcept;

// ".NAME.tmp-PID": the temporary sibling of `out` this process writes into.
std::filesystem::path sim_temp_folder(const std::filesystem::path& out);

// Removes temporary siblings of `out` left by sims that were killed outright (SIGKILL, power
// loss): those whose PID is gone and that hold a marker and nothing but a sim's outputs.
void remove_stale_sim_temp_folders(const std::filesystem::path& out) noexcept;

}  // namespace wavebench::cli
