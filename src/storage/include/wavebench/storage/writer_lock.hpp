#pragma once
// The one writer of a runs folder (issue #22): an exclusive flock(2) on the folder itself,
// held through a descriptor of the directory. A lock on a file inside it locked nothing once
// the file was unlinked (a second daemon then started and marked the first one's live run
// incomplete); the folder cannot be unlinked while it holds runs.
//
// Stores of one process share the lock (one descriptor per folder, counted); a forked child
// does not inherit it as its own: it takes the folder anew and is refused while the parent
// holds it. `.writer.lock` beside the runs only names the holder's process for the message.

#include <filesystem>
#include <memory>
#include <stdexcept>

namespace wavebench::storage {

// In the folder: the holder's process id, for the refusal's message.
inline constexpr const char* kWriterLockFile = ".writer.lock";

// Another process writes runs under the folder (a wavebenchd, a `wavebench run --out`).
struct RunStoreInUse : std::runtime_error {
  using std::runtime_error::runtime_error;
};

class WriterLock {
 public:
  // Throws RunStoreInUse naming the folder and, where known, the process holding it. Where the
  // file system has no flock (some network file systems) the folder is taken unguarded.
  explicit WriterLock(const std::filesystem::path& root);
  ~WriterLock();
  WriterLock(const WriterLock&) = delete;
  WriterLock& operator=(const WriterLock&) = delete;

  bool held() const { return shared_ != nullptr; }

  struct Shared;

 private:
  std::shared_ptr<Shared> shared_;
};

}  // namespace wavebench::storage
