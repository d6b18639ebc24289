// SocketCanBus on a real vcan0: frames both ways, kernel filters and timestamps, error frames,
// can-utils (candump/cansend) and a python-can peer seeing the same traffic.
#include <gtest/gtest.h>
#include <linux/can.h>
#include <linux/can/error.h>
#include <linux/can/raw.h>

#include <cstring>

#include "vcan_support.hpp"
#include "wavebench/can/socket_can_bus.hpp"
#include "wavebench/canopen/heartbeat_consumer.hpp"
#include "wavebench/canopen/nmt.hpp"
#include "wavebench/canopen/sdo_client.hpp"

namespace wavebench::can {
namespace {

using testing::kVcan;
using testing::run_until;

struct Collected {
  std::vector<Frame> frames;
  std::vector<BusEventKind> events;
  CanBus::Subscription f, e;
  explicit Collected(CanBus& bus)
      : f(bus.on_frame([this](const Frame& fr) { frames.push_back(fr); })),
        e(bus.on_event([this](const BusEvent& ev) { events.push_back(ev.kind); })) {}
};

TEST(VcanSocket, FramesCrossWithKernelTimestamps) {
  WAVEBENCH_REQUIRE_VCAN();
  boost::asio::io_context io;
  SocketCanBus a(io, kVcan);
  SocketCanBus b(io, kVcan);
  Collected rb(b), ra(a);
  const auto before = std::chrono::system_clock::now();
  a.send(Frame::make(0x601, {0x40, 0x18, 0x10, 0x01, 0, 0, 0, 0}));
  a.send(Frame::make(0x12345678, {0xAB}));
  Frame rtr;
  rtr.id = 0x701;
  rtr.rtr = true;
  rtr.len = 1;
  a.send(rtr);
  ASSERT_TRUE(run_until(io, [&] { return rb.frames.size() >= 3; }));
  EXPECT_EQ(to_string(rb.frames[0]), "601#4018100100000000");
  EXPECT_EQ(to_string(rb.frames[1]), "12345678#AB");
  EXPECT_EQ(to_string(rb.frames[2]), "701#R1");
  for (const auto& f : rb.frames) {
    // Kernel stamps are on the realtime clock: after the send began, before now.
    EXPECT_GE(f.timestamp, before - std::chrono::seconds(1));
    EXPECT_LE(f.timestamp, std::chrono::system_clock::now() + std::chrono::seconds(1));
  }
  EXPECT_LE(rb.frames[0].timestamp, rb.frames[2].timestamp);
  EXPECT_TRUE(ra.frames.empty()) << "own frames are not received unless asked for";
}

TEST(VcanSocket, KernelFiltersPassOnlyMatches) {
  WAVEBENCH_REQUIRE_VCAN();
  boost::asio::io_context io;
  SocketCanBus tx(io, kVcan);
  SocketCanBus rx(io, kVcan);
  const FrameFilter sdo_responses[] = {{0x580, 0x780, false}};
  rx.set_filters(sdo_responses);
  Collected r(rx);
  tx.send(Frame::make(0x601, {1}));
  tx.send(Frame::make(0x181, {2}));
  tx.send(Frame::make(0x5A3, {3}));  // the last one passes: no waiting for an absence
  ASSERT_TRUE(run_until(io, [&] { return !r.frames.empty(); }));
  io.restart();
  io.poll();
  ASSERT_EQ(r.frames.size(), 1U);
  EXPECT_EQ(to_string(r.frames[0]), "5A3#03");
}

TEST(VcanSocket, ReceiveOwnWhenAsked) {
  WAVEBENCH_REQUIRE_VCAN();
  boost::asio::io_context io;
  SocketCanBus a(io, kVcan);
  a.receive_own(true);
  Collected ra(a);
  a.send(Frame::make(0x100, {7}));
  ASSERT_TRUE(run_until(io, [&] { return !ra.frames.empty(); }));
  EXPECT_EQ(to_string(ra.frames[0]), "100#07");
}

TEST(VcanSocket, ErrorFramesBecomeBusEvents) {
  WAVEBENCH_REQUIRE_VCAN();
  boost::asio::io_context io;
  SocketCanBus bus(io, kVcan);
  Collected r(bus);
  // Inject controller error frames through a raw socket: vcan loops them back to every socket
  // whose error mask matches.
  const int fd = ::socket(PF_CAN, SOCK_RAW, CAN_RAW);
  ASSERT_GE(fd, 0);
  sockaddr_can addr{};
  addr.can_family = AF_CAN;
  addr.can_ifindex = static_cast<int>(if_nametoindex(kVcan));
  ASSERT_EQ(::bind(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr), 0);
  can_frame passive{};
  passive.can_id = CAN_ERR_FLAG | CAN_ERR_CRTL;
  passive.len = CAN_ERR_DLC;
  passive.data[1] = CAN_ERR_CRTL_TX_PASSIVE;
  can_frame busoff{};
  busoff.can_id = CAN_ERR_FLAG | CAN_ERR_BUSOFF;
  busoff.len = CAN_ERR_DLC;
  can_frame restarted{};
  restarted.can_id = CAN_ERR_FLAG | CAN_ERR_RESTARTED;
  restarted.len = CAN_ERR_DLC;
  for (const auto* f : {&passive, &busoff, &restarted}) {
    ASSERT_EQ(::write(fd, f, sizeof *f), static_cast<ssize_t>(sizeof *f)) << std::strerror(errno);
  }
  ::close(fd);
  ASSERT_TRUE(run_until(io, [&] { return r.events.size() >= 3; }));
  EXPECT_EQ(r.events, (std::vector<BusEventKind>{BusEventKind::error_passive, BusEventKind::bus_off,
                                                 BusEventKind::restarted}));
  EXPECT_TRUE(r.frames.empty()) << "error frames are events, not traffic";
}

TEST(VcanSocket, CandumpRecordsWhatWeSend) {
  WAVEBENCH_REQUIRE_VCAN();
  boost::asio::io_context io;
  SocketCanBus bus(io, kVcan);
  const int receivers = testing::registered_receivers();
  testing::ChildProcess candump({"candump", "-L", "-n", "4", kVcan},
                                "/tmp/wavebench_candump_" + std::to_string(::getpid()) + ".log");
  ASSERT_TRUE(candump.started());
  ASSERT_TRUE(run_until(io, [&] {
    return testing::registered_receivers() > receivers || candump.exited();
  })) << "candump never bound";
  ASSERT_FALSE(candump.exited()) << candump.output();
  const std::vector<Frame> sent = {Frame::make(0x000, {0x01, 0x00}), Frame::make(0x080, {}),
                                   Frame::make(0x601, {0x2B, 0x17, 0x10, 0x00, 0xA0, 0x0F, 0, 0}),
                                   Frame::make(0x1ABCDE01, {1, 2, 3})};
  for (const auto& f : sent) bus.send(f);
  ASSERT_TRUE(run_until(io, [&] { return candump.exited(); })) << candump.output();
  const auto lines = testing::candump_frames(candump.output());
  ASSERT_EQ(lines.size(), sent.size()) << candump.output();
  for (std::size_t i = 0; i < sent.size(); ++i) {
    EXPECT_EQ(lines[i], std::string(kVcan) + " " + to_string(sent[i]));
  }
}

TEST(VcanSocket, CansendFramesReachUs) {
  WAVEBENCH_REQUIRE_VCAN();
  boost::asio::io_context io;
  SocketCanBus bus(io, kVcan);
  Collected r(bus);
  for (const char* text : {"123#DEADBEEF", "12345678#01", "702#05"}) {
    testing::ChildProcess cansend({"cansend", kVcan, text}, "/dev/null");
    EXPECT_EQ(cansend.wait(), 0) << text;
  }
  ASSERT_TRUE(run_until(io, [&] { return r.frames.size() >= 3; }));
  EXPECT_EQ(to_string(r.frames[0]), "123#DEADBEEF");
  EXPECT_EQ(to_string(r.frames[1]), "12345678#01");
  EXPECT_EQ(to_string(r.frames[2]), "702#05");
}

constexpr const char* kPythonPeer = R"PY(
# A CANopen node 0x22 written with python-can: heartbeats (operational) every 100 ms, SDO
# expedited upload of 0x1018:01 and segmented upload of 0x1008; NMT stop ends it.
import can, struct, sys, threading, time
NODE = 0x22
NAME = b"python-can peer node"
stop = threading.Event()
bus = can.Bus(interface="socketcan", channel=sys.argv[1])
def beat():
    while not stop.is_set():
        bus.send(can.Message(arbitration_id=0x700 + NODE, data=[0x05], is_extended_id=False))
        stop.wait(0.1)
threading.Thread(target=beat, daemon=True).start()
toggle, offset = 0, 0
while not stop.is_set():
    m = bus.recv(timeout=1.0)
    if m is None or m.is_extended_id:
        continue
    if m.arbitration_id == 0 and len(m.data) == 2 and m.data[0] == 0x02 and m.data[1] in (0, NODE):
        stop.set()
        break
    if m.arbitration_id != 0x600 + NODE or len(m.data) != 8:
        continue
    cmd, idx, sub = m.data[0], m.data[1] | m.data[2] << 8, m.data[3]
    reply = None
    if cmd == 0x40 and (idx, sub) == (0x1018, 1):
        reply = bytes([0x43, m.data[1], m.data[2], sub]) + struct.pack("<I", 0x12345678)
    elif cmd == 0x40 and (idx, sub) == (0x1008, 0):
        reply = bytes([0x41, m.data[1], m.data[2], sub]) + struct.pack("<I", len(NAME))
        toggle, offset = 0, 0
    elif cmd & 0xE0 == 0x60:
        chunk = NAME[offset:offset + 7]
        offset += len(chunk)
        last = offset >= len(NAME)
        reply = bytes([(cmd & 0x10) | ((7 - len(chunk)) << 1) | int(last)]) + chunk.ljust(7, b"\0")
    elif cmd == 0x40:
        reply = bytes([0x80, m.data[1], m.data[2], sub]) + struct.pack("<I", 0x06020000)
    if reply is not None:
        bus.send(can.Message(arbitration_id=0x580 + NODE, data=reply, is_extended_id=False))
bus.shutdown()
)PY";

TEST(VcanSocket, PythonCanNodeAnswersSdoAndItsHeartbeatIsWatched) {
  WAVEBENCH_REQUIRE_VCAN();
  boost::asio::io_context io;
  SocketCanBus bus(io, kVcan);
  const std::string script = "/tmp/wavebench_can_peer_" + std::to_string(::getpid()) + ".py";
  {
    std::ofstream out(script);
    out << kPythonPeer;
  }
  int lost = 0;
  std::vector<canopen::NmtState> states;
  // Generous consumer time: Python under emulation is slow, and the test must only see the
  // silence after the node has stopped.
  canopen::HeartbeatConsumer consumer(
      bus, 0x22, std::chrono::milliseconds(4000),
      {[&](canopen::NodeId, canopen::NmtState s) noexcept { states.push_back(s); },
       [&](canopen::NodeId) noexcept { ++lost; }, nullptr});
  testing::ChildProcess peer({"/usr/bin/python3", script, kVcan}, script + ".log");
  ASSERT_TRUE(run_until(
      io, [&] { return consumer.armed() || peer.exited(); }, std::chrono::seconds(240)))
      << peer.output();
  ASSERT_TRUE(consumer.armed()) << peer.output();
  EXPECT_EQ(states.front(), canopen::NmtState::operational);

  canopen::SdoClient sdo(bus, 0x22, std::chrono::milliseconds(20000));
  EXPECT_EQ(sdo.read<std::uint32_t>(0x1018, 1), 0x12345678U);
  const auto name = sdo.upload(0x1008, 0);
  EXPECT_EQ(std::string(name.begin(), name.end()), "python-can peer node");
  std::error_code ec;
  sdo.upload(0x6000, 0, ec);
  EXPECT_EQ(ec, canopen::make_error_code(canopen::SdoAbort::no_object));

  canopen::NmtMaster(bus).send(canopen::NmtCommand::stop, 0x22);
  ASSERT_TRUE(run_until(
      io, [&] { return lost > 0; }, std::chrono::seconds(240)))
      << peer.output();
  EXPECT_EQ(lost, 1);
  EXPECT_TRUE(consumer.timed_out());
  EXPECT_EQ(peer.wait(), 0) << peer.output();
  std::remove(script.c_str());
}

}  // namespace
}  // namespace wavebench::can
