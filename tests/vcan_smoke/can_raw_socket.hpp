// A CAN_RAW socket on one interface, written against the kernel API only (not the project's CAN
// driver), so the smoke test is an independent check of what the VM's vcan0 provides.
#pragma once

#include <linux/can.h>
#include <linux/can/raw.h>
#include <sys/time.h>

#include <chrono>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace wavebench::vcan_smoke {

// True when `ifname` exists and a PF_CAN socket can be opened (the kernel has CAN support).
bool can_interface_available(const std::string& ifname);

// The interface MTU: CAN_MTU (16) for classic-only, CANFD_MTU (72) when CAN FD is enabled.
int interface_mtu(const std::string& ifname);

struct ReceivedFrame {
  canfd_frame frame{};
  bool is_fd = false;
  int msg_flags = 0;                     // MSG_DONTROUTE marks local loopback, MSG_CONFIRM own
  std::optional<timeval> timestamp;      // SCM_TIMESTAMP, when SO_TIMESTAMP is on
  std::optional<timespec> timestamp_ns;  // SCM_TIMESTAMPNS, when SO_TIMESTAMPNS is on
};

class CanRawSocket {
 public:
  explicit CanRawSocket(const std::string& ifname);
  ~CanRawSocket();
  CanRawSocket(const CanRawSocket&) = delete;
  CanRawSocket& operator=(const CanRawSocket&) = delete;

  void set_filters(const std::vector<can_filter>& filters);
  void set_join_filters(bool join);
  void set_recv_own_msgs(bool on);
  void set_loopback(bool on);
  void set_fd_frames(bool on);
  // SO_TIMESTAMP (timeval) or SO_TIMESTAMPNS (timespec): the kernel keeps one receive-timestamp
  // mode per socket, the later setting replaces the earlier.
  enum class Timestamps { kOff, kMicroseconds, kNanoseconds };
  void set_timestamps(Timestamps mode);

  void send(const can_frame& frame);
  void send(const canfd_frame& frame);

  // Waits at most `limit` for one frame. The limit only guards against a hang: tests order their
  // frames so that the expected one is already queued when they call this.
  std::optional<ReceivedFrame> receive(std::chrono::milliseconds limit);

  // The timestamp of the last frame read, through ioctl(SIOCGSTAMP); nullopt (ENOENT) before the
  // first frame. The first call switches the socket's stamping on. The kernel only records it
  // for sockets without SO_TIMESTAMP/SO_TIMESTAMPNS, which get theirs as control messages.
  std::optional<timeval> last_stamp_ioctl() const;

 private:
  template <typename T>
  void set_option(int level, int name, const T& value, const char* what);

  int fd_ = -1;
};

// Convenience builders for the frames the tests send.
can_frame classic_frame(canid_t id, const std::vector<std::uint8_t>& data);
canfd_frame fd_frame(canid_t id, std::uint8_t flags, const std::vector<std::uint8_t>& data);

}  // namespace wavebench::vcan_smoke
