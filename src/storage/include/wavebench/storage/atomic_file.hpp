#pragma once
// Whole-file replacement that a crash never leaves half-written: temp file in the same
// directory, fsync, rename over the target, fsync the directory.

#include <filesystem>
#include <string>
#include <string_view>

namespace wavebench::storage {

// Throws std::system_error naming the path.
void write_file_atomically(const std::filesystem::path& path, std::string_view content);

// The last resort for a small file that must not go on saying something false (status.json,
// results.json of a run that ends aborted) when a new file cannot be made beside it (a folder
// made read-only, a full disk): the existing file overwritten in place and synced. Never
// creates it. Not crash-safe (a crash in between leaves it short), hence only after
// write_file_atomically() failed. Throws std::system_error naming the path.
void overwrite_file_in_place(const std::filesystem::path& path, std::string_view content);

// The same for a file written as it goes (a twin's overlay over an hour-long run): appended
// to a temp file in the target's directory, which commit() syncs and renames over the target.
// Not committed (an error, an exception, the destructor first), the temp file is removed and
// the target is left as it was. Not copyable: owns the descriptor.
class AtomicFileWriter {
 public:
  // Throws std::system_error naming the temp file.
  explicit AtomicFileWriter(const std::filesystem::path& path);
  ~AtomicFileWriter();
  AtomicFileWriter(const AtomicFileWriter&) = delete;
  AtomicFileWriter& operator=(const AtomicFileWriter&) = delete;

  // Buffered; throws std::system_error when a write fails (the temp file is removed then).
  void append(std::string_view text);
  void commit();
  const std::filesystem::path& path() const { return path_; }

 private:
  void write_buffer();
  void write_all(const char* data, std::size_t size);
  [[noreturn]] void fail_and_discard(const std::string& what);

  std::filesystem::path path_, temp_;
  int fd_ = -1;
  std::string buffer_;
};

}  // namespace wavebench::storage
