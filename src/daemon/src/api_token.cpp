#include "wavebench/daemon/api_token.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
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

std::string new_token() {
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

std::string errno_text() {
  return std::strerror(errno);
}

}  // namespace

std::string read_token(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) {
    throw std::runtime_error("token file " + path.string() + ": cannot read (" + errno_text() +
                             ")");
  }
  std::stringstream text;
  text << in.rdbuf();
  auto token = trimmed(text.str());
  if (token.empty()) {
    throw std::runtime_error("token file " + path.string() + ": empty; expected a token");
  }
  return token;
}

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
    return read_token(path);
  }
  const std::string token = new_token();
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
