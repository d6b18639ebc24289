#include "wavebench/storage/atomic_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <string>
#include <system_error>

namespace wavebench::storage {

namespace {
constexpr std::size_t kBufferBytes = 1 << 16;

[[noreturn]] void fail(const std::string& what, const std::filesystem::path& path) {
  throw std::system_error(errno, std::generic_category(), what + " " + path.string());
}
}  // namespace

AtomicFileWriter::AtomicFileWriter(const std::filesystem::path& path)
    : path_(path),
      temp_(path.parent_path() /
            ("." + path.filename().string() + ".tmp" + std::to_string(::getpid()))) {
  fd_ = ::open(temp_.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd_ < 0) fail("atomic write: cannot create", temp_);
  buffer_.reserve(kBufferBytes);
}

AtomicFileWriter::~AtomicFileWriter() {
  if (fd_ >= 0) {
    ::close(fd_);
    ::unlink(temp_.c_str());
  }
}

// A failed write leaves no temp file behind (a full disk must not fill up with them).
void AtomicFileWriter::fail_and_discard(const std::string& what) {
  const int e = errno;
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
  ::unlink(temp_.c_str());
  errno = e;
  fail(what, temp_);
}

void AtomicFileWriter::write_buffer() {
  write_all(buffer_.data(), buffer_.size());
  buffer_.clear();
}

void AtomicFileWriter::write_all(const char* p, std::size_t left) {
  while (left > 0) {
    const ssize_t n = ::write(fd_, p, left);
    if (n < 0) {
      if (errno == EINTR) continue;
      fail_and_discard("atomic write: write");
    }
    p += n;
    left -= static_cast<std::size_t>(n);
  }
}

void AtomicFileWriter::append(std::string_view text) {
  if (fd_ < 0) {
    errno = EBADF;
    fail("atomic write: already closed", temp_);
  }
  if (buffer_.size() + text.size() < kBufferBytes) {
    buffer_.append(text);
    return;
  }
  write_buffer();
  write_all(text.data(), text.size());  // a large piece goes straight to the file
}

void AtomicFileWriter::commit() {
  if (fd_ < 0) {
    errno = EBADF;
    fail("atomic write: already closed", temp_);
  }
  write_buffer();
  if (::fsync(fd_) != 0) fail_and_discard("atomic write: fsync");
  const int fd = fd_;
  fd_ = -1;
  if (::close(fd) != 0) {
    const int e = errno;
    ::unlink(temp_.c_str());
    errno = e;
    fail("atomic write: close", temp_);
  }
  if (::rename(temp_.c_str(), path_.c_str()) != 0) {
    const int e = errno;
    ::unlink(temp_.c_str());
    errno = e;
    fail("atomic write: rename to", path_);
  }
  const std::filesystem::path dir = path_.parent_path().empty() ? "." : path_.parent_path();
  const int dfd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dfd >= 0) {
    ::fsync(dfd);  // best effort: some filesystems refuse fsync on a directory
    ::close(dfd);
  }
}

void write_file_atomically(const std::filesystem::path& path, std::string_view content) {
  AtomicFileWriter writer(path);
  writer.append(content);
  writer.commit();
}

void overwrite_file_in_place(const std::filesystem::path& path, std::string_view content) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_TRUNC | O_CLOEXEC | O_NOFOLLOW);
  if (fd < 0) fail("in-place write: cannot open", path);
  const char* p = content.data();
  std::size_t left = content.size();
  while (left > 0) {
    const ssize_t n = ::write(fd, p, left);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      const int e = errno;
      ::close(fd);
      errno = e;
      fail("in-place write: write", path);
    }
    p += n;
    left -= static_cast<std::size_t>(n);
  }
  if (::fsync(fd) != 0) {
    const int e = errno;
    ::close(fd);
    errno = e;
    fail("in-place write: fsync", path);
  }
  if (::close(fd) != 0) fail("in-place write: close", path);
}

}  // namespace wavebench::storage
