#include "wavebench/simdevices/pty_pair.hpp"

#include <pty.h>
#include <termios.h>
#include <unistd.h>

#include <cerrno>
#include <system_error>

namespace wavebench::simdevices {

PtyPair::PtyPair() {
  char name[256] = {};
  termios raw{};
  cfmakeraw(&raw);
  if (openpty(&master_, &slave_, name, &raw, nullptr) == -1) {
    throw std::system_error(errno, std::generic_category(), "openpty");
  }
  slave_path_ = name;
}

PtyPair::~PtyPair() {
  if (master_ >= 0) ::close(master_);
  if (slave_ >= 0) ::close(slave_);
}

int PtyPair::release_master() noexcept {
  const int fd = master_;
  master_ = -1;
  return fd;
}

}  // namespace wavebench::simdevices
