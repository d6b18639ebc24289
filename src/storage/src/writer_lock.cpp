#include "wavebench/storage/writer_lock.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <fstream>
#include <map>
#include <mutex>
#include <string>
#include <utility>
namespace wavebench::storage {

struct WriterLock::Shared {
  int fd = -1;
  pid_t pid = 0;  // the process that took it: a forked child's copy is not its own
  ~Shared() {
    if (fd >= 0) ::close(fd);
  }
};

namespace {

using FolderKey = std::pair<dev_t, ino_t>;

std::mutex& registry_mutex() {
  static std::mutex m;
  return m;
}
std::map<FolderKey, std::weak_ptr<WriterLock::Shared>>& registry() {
  static std::map<FolderKey, std::weak_ptr<WriterLock::Shared>> r;
  return r;
}

std::string holder_of(const std::filesystem::path& root) {
  std::ifstream in(root / kWriterLockFile);
  long pid = 0;
  if (in >> pid && pid > 0) return "process " + std::to_string(pid);
  return "another process";
}

void name_holder(const std::filesystem::path& root) {
  // Informational only: the lock is the folder's, this file may be deleted at no harm.
  const auto file = root / kWriterLockFile;
  const int fd = ::open(file.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC | O_NOFOLLOW, 0644);
  if (fd < 0) return;
  const std::string text = std::to_string(::getpid()) + "\n";
  const ssize_t written = ::write(fd, text.data(), text.size());
  static_cast<void>(written);
  ::close(fd);
}

}  // namespace

WriterLock::WriterLock(const std::filesystem::path& root) {
  const int fd = ::open(root.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) return;  // not readable: opening the index says what is wrong
  struct stat st {};
  if (::fstat(fd, &st) != 0) {
    ::close(fd);
    return;
  }
  const FolderKey key{st.st_dev, st.st_ino};
  std::lock_guard guard(registry_mutex());
  if (auto existing = registry()[key].lock(); existing && existing->pid == ::getpid()) {
    ::close(fd);
    shared_ = std::move(existing);
    return;
  }
  if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
    const int err = errno;
    ::close(fd);
    if (err != EWOULDBLOCK) return;  // no flock here: as before, unguarded
    throw RunStoreInUse("run store " + root.string() + ": in use by " + holder_of(root) +
                        " (a wavebenchd or a wavebench run writing runs there; the lock is the "
                        "folder's own, deleting " +
                        kWriterLockFile +
                        " does not release it); expected a folder no other "
                        "process writes");
  }
  shared_ = std::make_shared<Shared>();
  shared_->fd = fd;
  shared_->pid = ::getpid();
  registry()[key] = shared_;
  name_holder(root);
}

WriterLock::~WriterLock() {
  std::lock_guard guard(registry_mutex());
  shared_.reset();
}

}  // namespace wavebench::storage
