#include "can_raw_socket.hpp"

#include <linux/sockios.h>
#include <net/if.h>
#include <poll.h>
#include <sys/ioctl.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <system_error>

namespace wavebench::vcan_smoke {
namespace {

[[noreturn]] void throw_errno(const std::string& what) {
  throw std::system_error(errno, std::generic_category(), what);
}

}  // namespace

bool can_interface_available(const std::string& ifname) {
  if (if_nametoindex(ifname.c_str()) == 0) return false;
  const int fd = ::socket(PF_CAN, SOCK_RAW, CAN_RAW);
  if (fd < 0) return false;
  ::close(fd);
  return true;
}

int interface_mtu(const std::string& ifname) {
  const int fd = ::socket(PF_CAN, SOCK_RAW, CAN_RAW);
  if (fd < 0) throw_errno("socket(PF_CAN)");
  ifreq ifr{};
  std::strncpy(ifr.ifr_name, ifname.c_str(), IFNAMSIZ - 1);
  const int rc = ::ioctl(fd, SIOCGIFMTU, &ifr);
  const int saved = errno;
  ::close(fd);
  errno = saved;
  if (rc < 0) throw_errno("SIOCGIFMTU " + ifname);
  return ifr.ifr_mtu;
}

CanRawSocket::CanRawSocket(const std::string& ifname) {
  fd_ = ::socket(PF_CAN, SOCK_RAW | SOCK_CLOEXEC, CAN_RAW);
  if (fd_ < 0) throw_errno("socket(PF_CAN, SOCK_RAW, CAN_RAW)");
  sockaddr_can addr{};
  addr.can_family = AF_CAN;
  addr.can_ifindex = static_cast<int>(if_nametoindex(ifname.c_str()));
  if (addr.can_ifindex == 0) {
    ::close(fd_);
    throw std::invalid_argument("CAN interface '" + ifname + "' does not exist");
  }
  if (::bind(fd_, reinterpret_cast<const sockaddr*>(&addr), sizeof addr) < 0) {
    const int saved = errno;
    ::close(fd_);
    errno = saved;
    throw_errno("bind to " + ifname);
  }
}

CanRawSocket::~CanRawSocket() {
  if (fd_ >= 0) ::close(fd_);
}

template <typename T>
void CanRawSocket::set_option(int level, int name, const T& value, const char* what) {
  if (::setsockopt(fd_, level, name, &value, sizeof value) < 0) throw_errno(what);
}

void CanRawSocket::set_filters(const std::vector<can_filter>& filters) {
  const auto size = static_cast<socklen_t>(filters.size() * sizeof(can_filter));
  if (::setsockopt(fd_, SOL_CAN_RAW, CAN_RAW_FILTER, filters.data(), size) < 0) {
    throw_errno("CAN_RAW_FILTER");
  }
}

void CanRawSocket::set_join_filters(bool join) {
  set_option(SOL_CAN_RAW, CAN_RAW_JOIN_FILTERS, int{join}, "CAN_RAW_JOIN_FILTERS");
}

void CanRawSocket::set_recv_own_msgs(bool on) {
  set_option(SOL_CAN_RAW, CAN_RAW_RECV_OWN_MSGS, int{on}, "CAN_RAW_RECV_OWN_MSGS");
}

void CanRawSocket::set_loopback(bool on) {
  set_option(SOL_CAN_RAW, CAN_RAW_LOOPBACK, int{on}, "CAN_RAW_LOOPBACK");
}

void CanRawSocket::set_fd_frames(bool on) {
  set_option(SOL_CAN_RAW, CAN_RAW_FD_FRAMES, int{on}, "CAN_RAW_FD_FRAMES");
}

void CanRawSocket::set_timestamps(Timestamps mode) {
  switch (mode) {
    case Timestamps::kOff:
      set_option(SOL_SOCKET, SO_TIMESTAMP, int{0}, "SO_TIMESTAMP");
      break;
    case Timestamps::kMicroseconds:
      set_option(SOL_SOCKET, SO_TIMESTAMP, int{1}, "SO_TIMESTAMP");
      break;
    case Timestamps::kNanoseconds:
      set_option(SOL_SOCKET, SO_TIMESTAMPNS, int{1}, "SO_TIMESTAMPNS");
      break;
  }
}

void CanRawSocket::send(const can_frame& frame) {
  const ssize_t n = ::write(fd_, &frame, sizeof frame);
  if (n < 0) throw_errno("write(can_frame)");
  if (n != static_cast<ssize_t>(sizeof frame)) throw std::runtime_error("short CAN write");
}

void CanRawSocket::send(const canfd_frame& frame) {
  const ssize_t n = ::write(fd_, &frame, sizeof frame);
  if (n < 0) throw_errno("write(canfd_frame)");
  if (n != static_cast<ssize_t>(sizeof frame)) throw std::runtime_error("short CAN FD write");
}

std::optional<ReceivedFrame> CanRawSocket::receive(std::chrono::milliseconds limit) {
  pollfd pfd{fd_, POLLIN, 0};
  const int ready = ::poll(&pfd, 1, static_cast<int>(limit.count()));
  if (ready < 0) throw_errno("poll");
  if (ready == 0) return std::nullopt;

  ReceivedFrame out;
  iovec iov{&out.frame, sizeof out.frame};
  alignas(cmsghdr) char control[CMSG_SPACE(sizeof(timeval)) + CMSG_SPACE(sizeof(timespec))];
  msghdr msg{};
  msg.msg_iov = &iov;
  msg.msg_iovlen = 1;
  msg.msg_control = control;
  msg.msg_controllen = sizeof control;
  const ssize_t n = ::recvmsg(fd_, &msg, 0);
  if (n < 0) throw_errno("recvmsg");
  if (n == static_cast<ssize_t>(CANFD_MTU)) {
    out.is_fd = true;
  } else if (n != static_cast<ssize_t>(CAN_MTU)) {
    throw std::runtime_error("recvmsg returned " + std::to_string(n) +
                             " bytes, expected CAN_MTU (16) or CANFD_MTU (72)");
  }
  out.msg_flags = msg.msg_flags;
  for (cmsghdr* c = CMSG_FIRSTHDR(&msg); c != nullptr; c = CMSG_NXTHDR(&msg, c)) {
    if (c->cmsg_level != SOL_SOCKET) continue;
    if (c->cmsg_type == SCM_TIMESTAMP) {
      timeval tv{};
      std::memcpy(&tv, CMSG_DATA(c), sizeof tv);
      out.timestamp = tv;
    } else if (c->cmsg_type == SCM_TIMESTAMPNS) {
      timespec ts{};
      std::memcpy(&ts, CMSG_DATA(c), sizeof ts);
      out.timestamp_ns = ts;
    }
  }
  return out;
}

std::optional<timeval> CanRawSocket::last_stamp_ioctl() const {
  timeval tv{};
  if (::ioctl(fd_, SIOCGSTAMP, &tv) < 0) {
    if (errno == ENOENT) return std::nullopt;
    throw_errno("SIOCGSTAMP");
  }
  return tv;
}

can_frame classic_frame(canid_t id, const std::vector<std::uint8_t>& data) {
  if (data.size() > CAN_MAX_DLEN) throw std::invalid_argument("classic CAN data > 8 bytes");
  can_frame f{};
  f.can_id = id;
  f.len = static_cast<std::uint8_t>(data.size());
  std::memcpy(f.data, data.data(), data.size());
  return f;
}

canfd_frame fd_frame(canid_t id, std::uint8_t flags, const std::vector<std::uint8_t>& data) {
  if (data.size() > CANFD_MAX_DLEN) throw std::invalid_argument("CAN FD data > 64 bytes");
  canfd_frame f{};
  f.can_id = id;
  f.flags = flags;
  f.len = static_cast<std::uint8_t>(data.size());
  std::memcpy(f.data, data.data(), data.size());
  return f;
}

}  // namespace wavebench::vcan_smoke
