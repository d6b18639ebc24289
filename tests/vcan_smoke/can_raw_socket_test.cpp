// CAN_RAW semantics on a real vcan0: delivery, filters, loopback options, timestamps, CAN FD.
// Absence of a frame is never inferred from waiting: a sentinel frame that must pass is sent
// after the ones that must not, and has to be the first to arrive.
#include "can_raw_socket.hpp"

#include <gtest/gtest.h>
#include <sys/socket.h>
#include <time.h>

#include <cerrno>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <system_error>
#include <vector>

#include "rx_timestamping.hpp"
#include "vcan_fixture.hpp"

namespace wavebench::vcan_smoke {
namespace {

using Bytes = std::vector<std::uint8_t>;
using CanRawOnVcan = VcanTest;

ReceivedFrame next(CanRawSocket& socket) {
  auto r = socket.receive(kReceiveLimit);
  if (!r) throw std::runtime_error("no frame arrived on vcan0");
  return *r;
}

Bytes payload(const ReceivedFrame& r) {
  return Bytes(r.frame.data, r.frame.data + r.frame.len);
}

std::int64_t nanoseconds(const timespec& ts) {
  return std::int64_t{ts.tv_sec} * 1'000'000'000 + ts.tv_nsec;
}

std::int64_t realtime_ns() {
  timespec ts{};
  clock_gettime(CLOCK_REALTIME, &ts);
  return nanoseconds(ts);
}

TEST_F(CanRawOnVcan, ClassicFrameArrivesByteExactOnAnotherSocket) {
  CanRawSocket rx(kVcan);
  CanRawSocket tx(kVcan);
  tx.send(classic_frame(0x123, {0xDE, 0xAD, 0xBE, 0xEF}));

  const ReceivedFrame r = next(rx);
  EXPECT_FALSE(r.is_fd);
  EXPECT_EQ(r.frame.can_id, 0x123u);
  EXPECT_EQ(r.frame.len, 4);
  EXPECT_EQ(payload(r), (Bytes{0xDE, 0xAD, 0xBE, 0xEF}));
  // Frames from a local socket are marked as such; only the sender's copy carries MSG_CONFIRM.
  EXPECT_TRUE(r.msg_flags & MSG_DONTROUTE);
  EXPECT_FALSE(r.msg_flags & MSG_CONFIRM);
}

TEST_F(CanRawOnVcan, ExtendedAndRemoteFramesKeepTheirFlagsAndOrder) {
  CanRawSocket rx(kVcan);
  CanRawSocket tx(kVcan);
  tx.send(classic_frame(CAN_EFF_FLAG | 0x1F334455, {1, 2, 3, 4, 5, 6, 7, 8}));
  can_frame remote = classic_frame(CAN_RTR_FLAG | 0x7FF, {});
  remote.len = 3;  // a remote frame requests 3 bytes and carries none
  tx.send(remote);
  tx.send(classic_frame(0x000, {}));

  const ReceivedFrame a = next(rx);
  EXPECT_EQ(a.frame.can_id, CAN_EFF_FLAG | 0x1F334455u);
  EXPECT_EQ(payload(a), (Bytes{1, 2, 3, 4, 5, 6, 7, 8}));
  const ReceivedFrame b = next(rx);
  EXPECT_EQ(b.frame.can_id, CAN_RTR_FLAG | 0x7FFu);
  EXPECT_EQ(b.frame.len, 3);
  const ReceivedFrame c = next(rx);
  EXPECT_EQ(c.frame.can_id, 0x000u);
  EXPECT_EQ(c.frame.len, 0);
}

TEST_F(CanRawOnVcan, StandardMaskWithoutEffFlagAlsoMatchesExtendedIds) {
  CanRawSocket rx(kVcan);
  rx.set_filters({{0x123, CAN_SFF_MASK}});
  CanRawSocket tx(kVcan);
  tx.send(classic_frame(0x100, {1}));
  tx.send(classic_frame(0x124, {2}));
  tx.send(classic_frame(CAN_EFF_FLAG | 0x00000123, {3}));
  tx.send(classic_frame(CAN_EFF_FLAG | 0x10000123, {4}));
  tx.send(classic_frame(0x123, {5}));

  // The mask ignores the EFF flag and the upper 18 id bits, so both extended frames pass.
  EXPECT_EQ(next(rx).frame.can_id, CAN_EFF_FLAG | 0x00000123u);
  EXPECT_EQ(next(rx).frame.can_id, CAN_EFF_FLAG | 0x10000123u);
  const ReceivedFrame last = next(rx);
  EXPECT_EQ(last.frame.can_id, 0x123u);
  EXPECT_EQ(payload(last), Bytes{5});
}

TEST_F(CanRawOnVcan, EffFlagInMaskSeparatesStandardFromExtendedIds) {
  CanRawSocket standard(kVcan);
  standard.set_filters({{0x123, CAN_SFF_MASK | CAN_EFF_FLAG | CAN_RTR_FLAG}});
  CanRawSocket extended(kVcan);
  extended.set_filters({{CAN_EFF_FLAG | 0x123, CAN_EFF_MASK | CAN_EFF_FLAG | CAN_RTR_FLAG}});
  CanRawSocket tx(kVcan);
  tx.send(classic_frame(CAN_EFF_FLAG | 0x123, {1}));
  tx.send(classic_frame(CAN_RTR_FLAG | 0x123, {}));
  tx.send(classic_frame(0x123, {2}));
  tx.send(classic_frame(CAN_EFF_FLAG | 0x123, {3}));

  const ReceivedFrame s = next(standard);
  EXPECT_EQ(s.frame.can_id, 0x123u);
  EXPECT_EQ(payload(s), Bytes{2});
  const ReceivedFrame e1 = next(extended);
  EXPECT_EQ(e1.frame.can_id, CAN_EFF_FLAG | 0x123u);
  EXPECT_EQ(payload(e1), Bytes{1});
  const ReceivedFrame e2 = next(extended);
  EXPECT_EQ(payload(e2), Bytes{3});
}

TEST_F(CanRawOnVcan, InvertedFilterDropsOnlyItsId) {
  CanRawSocket rx(kVcan);
  rx.set_filters({{0x123 | CAN_INV_FILTER, CAN_SFF_MASK}});
  CanRawSocket tx(kVcan);
  tx.send(classic_frame(0x123, {1}));
  tx.send(classic_frame(0x124, {2}));

  const ReceivedFrame r = next(rx);
  EXPECT_EQ(r.frame.can_id, 0x124u);
  EXPECT_EQ(payload(r), Bytes{2});
}

TEST_F(CanRawOnVcan, SeveralFiltersAreOredUnlessJoined) {
  CanRawSocket any(kVcan);
  any.set_filters({{0x100, 0x7F0}, {0x200, 0x7FF}});
  CanRawSocket all(kVcan);
  all.set_filters({{0x100, 0x700}, {0x005, 0x00F}});
  all.set_join_filters(true);
  CanRawSocket tx(kVcan);
  for (const canid_t id : {0x0FFu, 0x10Au, 0x201u, 0x106u, 0x205u, 0x200u, 0x105u}) {
    tx.send(classic_frame(id, {}));
  }

  EXPECT_EQ(next(any).frame.can_id, 0x10Au);
  EXPECT_EQ(next(any).frame.can_id, 0x106u);
  EXPECT_EQ(next(any).frame.can_id, 0x200u);
  EXPECT_EQ(next(any).frame.can_id, 0x105u);
  // Joined: id & 0x700 == 0x100 and id & 0x00F == 0x005; only 0x105 satisfies both.
  EXPECT_EQ(next(all).frame.can_id, 0x105u);
}

TEST_F(CanRawOnVcan, SenderSeesItsOwnFramesOnlyWithRecvOwnMsgs) {
  CanRawSocket tx(kVcan);
  CanRawSocket other(kVcan);
  tx.send(classic_frame(0x010, {}));
  other.send(classic_frame(0x020, {}));
  EXPECT_EQ(next(tx).frame.can_id, 0x020u);

  tx.set_recv_own_msgs(true);
  tx.send(classic_frame(0x030, {7}));
  const ReceivedFrame own = next(tx);
  EXPECT_EQ(own.frame.can_id, 0x030u);
  EXPECT_TRUE(own.msg_flags & MSG_CONFIRM);
  EXPECT_TRUE(own.msg_flags & MSG_DONTROUTE);
}

TEST_F(CanRawOnVcan, LoopbackOffHidesFramesFromOtherLocalSockets) {
  CanRawSocket rx(kVcan);
  CanRawSocket quiet(kVcan);
  quiet.set_loopback(false);
  CanRawSocket tx(kVcan);
  quiet.send(classic_frame(0x111, {}));
  tx.send(classic_frame(0x222, {}));
  EXPECT_EQ(next(rx).frame.can_id, 0x222u);
}

TEST_F(CanRawOnVcan, TimestampsLieBetweenSendAndReceiveAndAgreeAcrossApis) {
  const RxTimestampingOn stamping(kVcan);
  CanRawSocket rx_us(kVcan);
  rx_us.set_timestamps(CanRawSocket::Timestamps::kMicroseconds);
  CanRawSocket rx_ns(kVcan);
  rx_ns.set_timestamps(CanRawSocket::Timestamps::kNanoseconds);
  CanRawSocket rx_ioctl(kVcan);
  EXPECT_FALSE(rx_ioctl.last_stamp_ioctl().has_value()) << "a stamp before any frame was read";
  CanRawSocket tx(kVcan);

  std::int64_t previous = 0;
  for (int i = 0; i < 3; ++i) {
    const std::int64_t before = realtime_ns();
    tx.send(classic_frame(0x300 + static_cast<canid_t>(i), {static_cast<std::uint8_t>(i)}));
    const ReceivedFrame us = next(rx_us);
    const ReceivedFrame ns = next(rx_ns);
    const ReceivedFrame plain = next(rx_ioctl);
    const std::int64_t after = realtime_ns();

    ASSERT_TRUE(us.timestamp.has_value()) << "no SCM_TIMESTAMP";
    EXPECT_FALSE(us.timestamp_ns.has_value());
    ASSERT_TRUE(ns.timestamp_ns.has_value()) << "no SCM_TIMESTAMPNS";
    EXPECT_FALSE(ns.timestamp.has_value());
    const std::int64_t stamp = nanoseconds(*ns.timestamp_ns);
    EXPECT_GE(stamp, before);
    EXPECT_LE(stamp, after);
    EXPECT_GE(stamp, previous);
    previous = stamp;
    // Every receiver gets a clone of one skb, so both sockets and SIOCGSTAMP report one time.
    EXPECT_EQ(us.timestamp->tv_sec, ns.timestamp_ns->tv_sec);
    EXPECT_EQ(us.timestamp->tv_usec, ns.timestamp_ns->tv_nsec / 1000);
    EXPECT_FALSE(plain.timestamp.has_value());
    const std::optional<timeval> ioctl_stamp = rx_ioctl.last_stamp_ioctl();
    ASSERT_TRUE(ioctl_stamp.has_value()) << "SIOCGSTAMP after a frame was read";
    EXPECT_EQ(ioctl_stamp->tv_sec, us.timestamp->tv_sec);
    EXPECT_EQ(ioctl_stamp->tv_usec, us.timestamp->tv_usec);
  }
}

TEST_F(CanRawOnVcan, FdFrameWith64BytesRoundTripsAndBypassesClassicSockets) {
  if (interface_mtu(kVcan) != static_cast<int>(CANFD_MTU)) {
    GTEST_SKIP() << kVcan << " is not CAN FD capable (ip link set " << kVcan << " mtu 72)";
  }
  CanRawSocket fd_rx(kVcan);
  fd_rx.set_fd_frames(true);
  CanRawSocket classic_rx(kVcan);
  CanRawSocket tx(kVcan);
  tx.set_fd_frames(true);
  Bytes data(64);
  for (std::size_t i = 0; i < data.size(); ++i) data[i] = static_cast<std::uint8_t>(i * 3 + 1);
  tx.send(fd_frame(CAN_EFF_FLAG | 0x18DAF110, CANFD_BRS, data));
  tx.send(classic_frame(0x7FF, {0xAA}));

  const ReceivedFrame fd = next(fd_rx);
  EXPECT_TRUE(fd.is_fd);
  EXPECT_EQ(fd.frame.can_id, CAN_EFF_FLAG | 0x18DAF110u);
  EXPECT_EQ(fd.frame.len, 64);
  EXPECT_EQ(payload(fd), data);
  EXPECT_EQ(fd.frame.flags & (CANFD_BRS | CANFD_ESI), CANFD_BRS);
  const ReceivedFrame classic_on_fd = next(fd_rx);
  EXPECT_FALSE(classic_on_fd.is_fd);
  EXPECT_EQ(classic_on_fd.frame.can_id, 0x7FFu);

  // A socket without CAN_RAW_FD_FRAMES never sees FD frames: the classic frame comes first.
  const ReceivedFrame first_classic = next(classic_rx);
  EXPECT_FALSE(first_classic.is_fd);
  EXPECT_EQ(first_classic.frame.can_id, 0x7FFu);
}

TEST_F(CanRawOnVcan, ClassicSocketRefusesFdWrites) {
  CanRawSocket tx(kVcan);
  try {
    tx.send(fd_frame(0x123, 0, {1, 2, 3}));
    FAIL() << "a CAN FD write on a socket without CAN_RAW_FD_FRAMES succeeded";
  } catch (const std::system_error& e) {
    EXPECT_EQ(e.code().value(), EINVAL) << e.what();
  }
}

}  // namespace
}  // namespace wavebench::vcan_smoke
