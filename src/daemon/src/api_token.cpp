#include "wavebench/daemon/api_token.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <random>
#include <sstream>
#include <stdexcept>

namespace wavebench::daemon {

namespace {

std::string trimmed(std::string text) {
  const auto first = text.find_first_not_of(" \t\r\n");
  if (first == std::string::npos) return {};
  const auto last = text.find_last_not_of(" \t\r\n");
  return text.substr(first, last - first + 1);
}

}  // namespace

std::string random_hex_token() {
  std::random_device device;  // /dev/urandom on Linux
  static constexpr char kHex[] = "0123456789abcdef";
  std::string token;
  for (int i = 0; i < 32; ++i) {
    const auto byte = device() & 0xffu;
    token += kHex[byte >> 4];
    token += kHex[byte & 0xfu];
  }
  return token;
}

namespace {

std::string errno_text() {
  return std::strerror(errno);
}

// The file's text and status, read through one descriptor (no check-then-open race); a FIFO
// or device is refused without blocking on it.
struct TokenFileText {
  std::string text;
  struct stat st {};
};

TokenFileText read_token_file(const std::filesystem::path& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK | O_NOCTTY);
  if (fd < 0) {
    throw std::runtime_error("token file " + path.string() + ": cannot read (" + errno_text() +
                             ")");
  }
  TokenFileText r;
  const auto fail = [&](const std::string& why) {
    ::close(fd);
    throw std::runtime_error("token file " + path.string() + ": " + why);
  };
  if (::fstat(fd, &r.st) != 0) fail("cannot stat (" + errno_text() + ")");
  const auto refuse = [&](const std::string& why) {
    ::close(fd);
    throw TokenFileRefused("token file " + path.string() + ": " + why);
  };
  if (!S_ISREG(r.st.st_mode)) refuse("not a regular file; expected a file holding the token");
  if (r.st.st_size > static_cast<off_t>(kMaxTokenFileBytes)) {
    refuse(std::to_string(r.st.st_size) + " bytes; expected a token of at most " +
           std::to_string(kMaxTokenFileBytes) + " bytes");
  }
  char buffer[kMaxTokenFileBytes + 1];
  std::size_t used = 0;
  for (;;) {
    const auto n = ::read(fd, buffer + used, sizeof buffer - used);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) fail("cannot read (" + errno_text() + ")");
    if (n == 0 || (used += static_cast<std::size_t>(n)) == sizeof buffer) break;
  }
  ::close(fd);
  if (used > kMaxTokenFileBytes) {
    throw std::runtime_error("token file " + path.string() + ": grew past " +
                             std::to_string(kMaxTokenFileBytes) + " bytes while read");
  }
  r.text.assign(buffer, used);
  return r;
}

std::string token_of(const std::filesystem::path& path, const std::string& text) {
  auto token = trimmed(text);
  if (token.empty()) {
    throw TokenFileRefused("token file " + path.string() + ": empty; expected a token");
  }
  for (const char c : token) {
    if (c <= ' ' || c > '~') {
      throw TokenFileRefused("token file " + path.string() +
                             ": holds a space, control or non-ASCII character; expected one "
                             "token of printable ASCII characters");
    }
  }
  return token;
}

}  // namespace

std::string read_token(const std::filesystem::path& path) {
  return token_of(path, read_token_file(path).text);
}

namespace {

std::string checked_daemon_token(const std::filesystem::path& path) {
  const auto file = read_token_file(path);
  const auto mode = file.st.st_mode & 0777;
  if ((mode & 077) != 0) {
    char octal[8];
    std::snprintf(octal, sizeof octal, "%04o", mode);
    throw TokenFileRefused("token file " + path.string() + ": mode " + octal +
                           " lets other users read or change it; expected 0600 (chmod 600 " +
                           path.string() + ")");
  }
  if (file.st.st_uid != ::geteuid()) {
    throw TokenFileRefused("token file " + path.string() + ": owned by uid " +
                           std::to_string(file.st.st_uid) + "; expected the daemon's own uid " +
                           std::to_string(::geteuid()));
  }
  auto token = token_of(path, file.text);
  if (token.size() < kMinTokenLength) {
    throw TokenFileRefused("token file " + path.string() + ": a token of " +
                           std::to_string(token.size()) + " characters; expected at least " +
                           std::to_string(kMinTokenLength) +
                           " (delete the file and the daemon creates a random one)");
  }
  return token;
}

}  // namespace

std::string load_or_create_token(const std::filesystem::path& path) {
  if (!path.parent_path().empty()) {
    std::error_code ec;
    std::filesystem::create_directories(path.parent_path(), ec);
  }
  // O_EXCL: a token someone else just created is read, never overwritten.
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
  if (fd < 0) {
    if (errno != EEXIST) {
      throw std::runtime_error("token file " + path.string() + ": cannot create (" + errno_text() +
                               ")");
    }
    return checked_daemon_token(path);
  }
  const std::string token = random_hex_token();
  const std::string line = token + "\n";
  const bool ok = ::write(fd, line.data(), line.size()) == static_cast<ssize_t>(line.size()) &&
                  ::fsync(fd) == 0;
  const std::string error = ok ? std::string() : errno_text();
  ::close(fd);
  if (!ok) {
    ::unlink(path.c_str());
    throw std::runtime_error("token file " + path.string() + ": cannot write (" + error + ")");
  }
  return token;
}

bool bearer_matches(std::string_view authorization, std::string_view token) {
  constexpr std::string_view kScheme = "Bearer ";
  if (token.empty() || authorization.size() != kScheme.size() + token.size()) return false;
  if (authorization.substr(0, kScheme.size()) != kScheme) return false;
  const auto given = authorization.substr(kScheme.size());
  unsigned difference = 0;
  for (std::size_t i = 0; i < token.size(); ++i) {
    difference |= static_cast<unsigned>(static_cast<unsigned char>(given[i]) ^
                                        static_cast<unsigned char>(token[i]));
  }
  return difference == 0;
}

std::filesystem::path default_token_file() {
  if (const char* env = std::getenv("WAVEBENCH_TOKEN_FILE"); env && *env) return env;
  if (const char* home = std::getenv("HOME"); home && *home) {
    return std::filesystem::path(home) / ".config" / "wavebench" / "daemon.token";
  }
  return "wavebench-daemon.token";
}

}  // namespace wavebench::daemon
