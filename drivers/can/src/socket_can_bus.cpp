#include "wavebench/can/socket_can_bus.hpp"

#include <fcntl.h>
#include <linux/can.h>
#include <linux/can/error.h>
#include <linux/can/raw.h>
#include <net/if.h>
#include <sys/ioctl.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <vector>

#include "wavebench/can/error_frame.hpp"

namespace wavebench::can {

namespace {

[[noreturn]] void fail(const std::string& interface_name, const std::string& step, int err) {
  std::string what = "SocketCAN interface '" + interface_name + "': " + step;
  if (err == EAFNOSUPPORT)
    what += " (this kernel has no CAN support: load can/can_raw or use a VM)";
  if (err == ENODEV) what += " (no such interface: create it, e.g. `ip link add vcan0 type vcan`)";
  throw std::system_error(err, std::generic_category(), what);
}

int open_socket(const std::string& interface_name) {
  if (interface_name.empty() || interface_name.size() >= IFNAMSIZ) {
    throw std::invalid_argument("SocketCAN interface name '" + interface_name +
                                "': expected 1 to " + std::to_string(IFNAMSIZ - 1) + " characters");
  }
  const int fd = ::socket(PF_CAN, SOCK_RAW | SOCK_NONBLOCK | SOCK_CLOEXEC, CAN_RAW);
  if (fd < 0) fail(interface_name, "socket(PF_CAN, SOCK_RAW, CAN_RAW)", errno);
  auto close_and_fail = [&](const std::string& step) {
    const int err = errno;
    ::close(fd);
    fail(interface_name, step, err);
  };
  ifreq ifr{};
  std::memcpy(ifr.ifr_name, interface_name.c_str(), interface_name.size() + 1);
  if (::ioctl(fd, SIOCGIFINDEX, &ifr) < 0) close_and_fail("SIOCGIFINDEX");
  const int on = 1;
  if (::setsockopt(fd, SOL_SOCKET, SO_TIMESTAMPNS, &on, sizeof on) < 0) {
    close_and_fail("setsockopt(SO_TIMESTAMPNS)");
  }
  const can_err_mask_t err_mask = CAN_ERR_MASK;
  if (::setsockopt(fd, SOL_CAN_RAW, CAN_RAW_ERR_FILTER, &err_mask, sizeof err_mask) < 0) {
    close_and_fail("setsockopt(CAN_RAW_ERR_FILTER)");
  }
  sockaddr_can addr{};
  addr.can_family = AF_CAN;
  addr.can_ifindex = ifr.ifr_ifindex;
  if (::bind(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr) < 0) close_and_fail("bind");
  return fd;
}

Frame from_kernel(const can_frame& kf) {
  Frame f;
  f.error = (kf.can_id & CAN_ERR_FLAG) != 0U;
  f.extended = !f.error && (kf.can_id & CAN_EFF_FLAG) != 0U;
  f.rtr = !f.error && (kf.can_id & CAN_RTR_FLAG) != 0U;
  f.id = kf.can_id & (f.extended || f.error ? CAN_EFF_MASK : CAN_SFF_MASK);
  f.len = std::min<std::uint8_t>(kf.len, CAN_MAX_DLEN);
  std::copy_n(kf.data, f.len, f.data.begin());
  return f;
}

}  // namespace

SocketCanBus::SocketCanBus(boost::asio::io_context& io, std::string interface_name)
    : io_(io),
      interface_name_(std::move(interface_name)),
      socket_(io, open_socket(interface_name_)),
      alive_(std::make_shared<bool>(true)) {
  start_read();
}

SocketCanBus::~SocketCanBus() {
  *alive_ = false;
  boost::system::error_code ignored;
  socket_.cancel(ignored);
  socket_.close(ignored);
}

void SocketCanBus::send(const Frame& frame, std::error_code& ec) noexcept {
  ec.clear();
  if (frame.len > CAN_MAX_DLEN || frame.error) {
    ec = std::make_error_code(std::errc::invalid_argument);
    return;
  }
  can_frame kf{};
  kf.can_id = frame.raw_id();
  kf.len = frame.len;
  std::copy_n(frame.data.begin(), frame.len, kf.data);
  for (;;) {
    const ssize_t n = ::write(socket_.native_handle(), &kf, sizeof kf);
    if (n == static_cast<ssize_t>(sizeof kf)) return;
    if (n < 0 && errno == EINTR) continue;
    ec = std::error_code(n < 0 ? errno : EIO, std::generic_category());
    return;
  }
}

void SocketCanBus::set_filters(std::span<const FrameFilter> filters) {
  std::vector<can_filter> kernel;
  kernel.reserve(filters.size());
  for (const auto& f : filters) {
    can_filter k{};
    k.can_id = f.id | (f.inverted ? CAN_INV_FILTER : 0U);
    k.can_mask = f.mask;
    kernel.push_back(k);
  }
  const auto size = static_cast<socklen_t>(kernel.size() * sizeof(can_filter));
  if (::setsockopt(socket_.native_handle(), SOL_CAN_RAW, CAN_RAW_FILTER,
                   kernel.empty() ? nullptr : kernel.data(), size) < 0) {
    throw std::system_error(errno, std::generic_category(),
                            "SocketCAN interface '" + interface_name_ + "': CAN_RAW_FILTER");
  }
}

void SocketCanBus::receive_own(bool on) {
  const int value = on ? 1 : 0;
  if (::setsockopt(socket_.native_handle(), SOL_CAN_RAW, CAN_RAW_RECV_OWN_MSGS, &value,
                   sizeof value) < 0) {
    throw std::system_error(errno, std::generic_category(),
                            "SocketCAN interface '" + interface_name_ + "': RECV_OWN_MSGS");
  }
}

void SocketCanBus::start_read() {
  std::weak_ptr<bool> alive = alive_;
  socket_.async_wait(boost::asio::posix::stream_descriptor::wait_read,
                     [this, alive](const boost::system::error_code& ec) {
                       auto a = alive.lock();
                       if (!a || !*a || ec == boost::asio::error::operation_aborted) return;
                       read_ready();
                       if (*a) start_read();
                     });
}

void SocketCanBus::read_ready() noexcept {
  auto alive = alive_;
  // Drain what is queued, but bounded so one busy socket cannot starve the io_context.
  for (int i = 0; i < 256 && *alive; ++i) {
    can_frame kf{};
    iovec iov{&kf, sizeof kf};
    alignas(cmsghdr) char control[CMSG_SPACE(sizeof(timespec)) * 2];
    msghdr msg{};
    msg.msg_iov = &iov;
    msg.msg_iovlen = 1;
    msg.msg_control = control;
    msg.msg_controllen = sizeof control;
    const ssize_t n = ::recvmsg(socket_.native_handle(), &msg, MSG_DONTWAIT);
    if (n < 0) {
      if (errno == EINTR) continue;
      return;  // EAGAIN: drained
    }
    if (static_cast<std::size_t>(n) < sizeof kf) continue;
    Frame f = from_kernel(kf);
    for (cmsghdr* c = CMSG_FIRSTHDR(&msg); c != nullptr; c = CMSG_NXTHDR(&msg, c)) {
      if (c->cmsg_level == SOL_SOCKET && c->cmsg_type == SO_TIMESTAMPNS) {
        timespec ts{};
        std::memcpy(&ts, CMSG_DATA(c), sizeof ts);
        f.timestamp = std::chrono::system_clock::time_point(
            std::chrono::duration_cast<std::chrono::system_clock::duration>(
                std::chrono::seconds(ts.tv_sec) + std::chrono::nanoseconds(ts.tv_nsec)));
      }
    }
    if (f.timestamp == std::chrono::system_clock::time_point{}) {
      f.timestamp = std::chrono::system_clock::now();
    }
    if (f.error) {
      try {
        for (const auto& ev : classify_error_frame(f)) deliver(ev);
      } catch (...) {
      }
    } else {
      deliver(f);
    }
  }
}

}  // namespace wavebench::can
