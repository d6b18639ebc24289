// can-utils against our own CAN_RAW sockets on vcan0: cansend's frames arrive as its syntax says,
// candump prints exactly the frames (and kernel timestamps) our sockets see. Python peers and
// the project's CAN tests rely on both tools inside the VM.
#include <gtest/gtest.h>
#include <sys/time.h>

#include <chrono>
#include <cstdio>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "can_raw_socket.hpp"
#include "can_utils_process.hpp"
#include "rx_timestamping.hpp"
#include "vcan_fixture.hpp"

namespace wavebench::vcan_smoke {
namespace {

using Bytes = std::vector<std::uint8_t>;

class CanUtilsOnVcan : public VcanTest {
 protected:
  void SetUp() override {
    VcanTest::SetUp();
    if (IsSkipped()) return;
    ASSERT_TRUE(program_on_path("candump")) << "candump (can-utils) not on PATH";
    ASSERT_TRUE(program_on_path("cansend")) << "cansend (can-utils) not on PATH";
  }
};

ReceivedFrame next(CanRawSocket& socket) {
  auto r = socket.receive(kReceiveLimit);
  if (!r) throw std::runtime_error("no frame arrived on vcan0");
  return *r;
}

Bytes payload(const ReceivedFrame& r) {
  return Bytes(r.frame.data, r.frame.data + r.frame.len);
}

// Starts candump and returns once its socket is registered with the CAN core, so that frames
// sent afterwards reach it. The deadline only turns a broken candump into a failure, not a hang.
std::unique_ptr<BackgroundCommand> start_candump(const std::string& args) {
  const int before = registered_receivers(kVcan);
  auto candump = std::make_unique<BackgroundCommand>("exec candump " + args);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (registered_receivers(kVcan) <= before) {
    if (std::chrono::steady_clock::now() > deadline) {
      throw std::runtime_error("candump " + args + " never registered a receiver on vcan0");
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return candump;
}

struct LogLine {
  std::string timestamp;  // "sec.usec" as printed
  std::string frame;      // "vcan0 123#DEADBEEF"
};

std::vector<LogLine> parse_log(const std::string& output) {
  std::vector<LogLine> lines;
  std::istringstream in(output);
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    const auto close = line.find(") ");
    if (line.front() != '(' || close == std::string::npos) {
      lines.push_back({"", line});  // not a log line: kept so the comparison shows it
      continue;
    }
    lines.push_back({line.substr(1, close - 1), line.substr(close + 2)});
  }
  return lines;
}

std::string stamp_text(const timeval& tv) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%lld.%06ld", static_cast<long long>(tv.tv_sec),
                static_cast<long>(tv.tv_usec));
  return buf;
}

bool fd_capable() {
  return interface_mtu(kVcan) == static_cast<int>(CANFD_MTU);
}

struct CansendCase {
  std::string text;
  canid_t id;
  int len;
  Bytes data;
};

TEST_F(CanUtilsOnVcan, CansendFramesArriveAsTheirSyntaxSays) {
  CanRawSocket rx(kVcan);
  const std::vector<CansendCase> cases = {
      {"123#DEADBEEF", 0x123, 4, {0xDE, 0xAD, 0xBE, 0xEF}},
      {"1F334455#1122334455667788",
       CAN_EFF_FLAG | 0x1F334455,
       8,
       {0x11, 0x22, 0x33, 0x44, 0x55, 0x66, 0x77, 0x88}},
      {"5A1#11.2233.44556677.88", 0x5A1, 8, {0x11, 0x22, 0x33, 0x44, 0x55, 0x66, 0x77, 0x88}},
      {"5AA#", 0x5AA, 0, {}},
      {"123#R", CAN_RTR_FLAG | 0x123, 0, {}},
      {"00000123#R3", CAN_EFF_FLAG | CAN_RTR_FLAG | 0x123, 3, {}},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.text);
    const CommandResult sent = run_command("cansend vcan0 " + c.text);
    ASSERT_EQ(sent.exit_status, 0) << sent.output;
    const ReceivedFrame r = next(rx);
    EXPECT_FALSE(r.is_fd);
    EXPECT_EQ(r.frame.can_id, c.id);
    EXPECT_EQ(r.frame.len, c.len);
    if (!(c.id & CAN_RTR_FLAG)) {
      EXPECT_EQ(payload(r), c.data);
    }
  }
}

TEST_F(CanUtilsOnVcan, CansendFdFrameCarriesFlagsAndData) {
  if (!fd_capable()) GTEST_SKIP() << "vcan0 is not CAN FD capable";
  CanRawSocket rx(kVcan);
  rx.set_fd_frames(true);
  const CommandResult sent = run_command("cansend vcan0 213##311223344");
  ASSERT_EQ(sent.exit_status, 0) << sent.output;
  const ReceivedFrame r = next(rx);
  EXPECT_TRUE(r.is_fd);
  EXPECT_EQ(r.frame.can_id, 0x213u);
  EXPECT_EQ(r.frame.flags & (CANFD_BRS | CANFD_ESI), CANFD_BRS | CANFD_ESI);
  EXPECT_EQ(payload(r), (Bytes{0x11, 0x22, 0x33, 0x44}));
}

TEST_F(CanUtilsOnVcan, CansendRejectsMalformedFramesAndSendsNothing) {
  CanRawSocket rx(kVcan);
  for (const char* bad : {"12G#00", "123#1", "1234#00"}) {
    const CommandResult r = run_command(std::string("cansend vcan0 '") + bad + "'");
    EXPECT_NE(r.exit_status, 0) << bad << " was accepted: " << r.output;
  }
  ASSERT_EQ(run_command("cansend vcan0 7FF#01").exit_status, 0);
  const ReceivedFrame first = next(rx);
  EXPECT_EQ(first.frame.can_id, 0x7FFu);
  EXPECT_EQ(payload(first), Bytes{0x01});
}

TEST_F(CanUtilsOnVcan, CandumpPrintsTheFramesAndTimestampsOurSocketSees) {
  const RxTimestampingOn stamping(kVcan);
  CanRawSocket rx(kVcan);
  rx.set_timestamps(CanRawSocket::Timestamps::kMicroseconds);
  // candump's "123:7FF" is the kernel's {0x123, 0x7FF}: the mask has no EFF flag, so an
  // extended 0x00000123 passes as well.
  auto candump = start_candump("-L -n 3 -T 60000 vcan0,123:7FF");
  CanRawSocket tx(kVcan);
  tx.send(classic_frame(0x100, {0x01}));
  tx.send(classic_frame(0x123, {0x02, 0x03}));
  tx.send(classic_frame(0x124, {0x04}));
  tx.send(classic_frame(CAN_EFF_FLAG | 0x123, {0x05}));
  tx.send(classic_frame(0x123, {}));

  std::vector<LogLine> expected;
  for (int i = 0; i < 5; ++i) {
    const ReceivedFrame r = next(rx);
    ASSERT_TRUE(r.timestamp.has_value());
    if ((r.frame.can_id & CAN_SFF_MASK) == 0x123) {
      expected.push_back({stamp_text(*r.timestamp), candump_log_text(kVcan, r.frame, r.is_fd)});
    }
  }
  ASSERT_EQ(expected.size(), 3u);
  EXPECT_EQ(expected[0].frame, "vcan0 123#0203");
  EXPECT_EQ(expected[1].frame, "vcan0 00000123#05");
  EXPECT_EQ(expected[2].frame, "vcan0 123#");

  const CommandResult dumped = candump->finish();
  EXPECT_EQ(dumped.exit_status, 0) << dumped.output;
  const std::vector<LogLine> lines = parse_log(dumped.output);
  ASSERT_EQ(lines.size(), expected.size()) << dumped.output;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    EXPECT_EQ(lines[i].frame, expected[i].frame);
    // One skb is cloned to every receiver, so candump reports our socket's timestamp exactly.
    EXPECT_EQ(lines[i].timestamp, expected[i].timestamp) << lines[i].frame;
  }
}

TEST_F(CanUtilsOnVcan, CandumpPrintsRemoteExtendedAndFdFrames) {
  const bool fd = fd_capable();
  CanRawSocket rx(kVcan);
  rx.set_fd_frames(fd);
  auto candump = start_candump(std::string("-L -n ") + (fd ? "4" : "3") + " -T 60000 vcan0");
  CanRawSocket tx(kVcan);
  tx.set_fd_frames(fd);
  can_frame remote = classic_frame(CAN_RTR_FLAG | 0x7DF, {});
  remote.len = 2;
  tx.send(remote);
  tx.send(classic_frame(CAN_EFF_FLAG | 0x0CF00400, {0xF0, 0xFF, 0x7D, 0x1F, 0x1F}));
  tx.send(classic_frame(0x000, {0x00, 0xFF}));
  if (fd) {
    Bytes data(12);
    for (std::size_t i = 0; i < data.size(); ++i) data[i] = static_cast<std::uint8_t>(0xA0 + i);
    tx.send(fd_frame(0x345, CANFD_BRS, data));
  }
  std::vector<std::string> expected = {"vcan0 7DF#R2", "vcan0 0CF00400#F0FF7D1F1F",
                                       "vcan0 000#00FF"};
  for (const auto& text : expected) {
    const ReceivedFrame r = next(rx);
    EXPECT_EQ(candump_log_text(kVcan, r.frame, r.is_fd), text);
  }
  if (fd) {
    // The flags nibble is printed as received: kernels with CAN XL support add CANFD_FDF (4).
    const ReceivedFrame r = next(rx);
    ASSERT_TRUE(r.is_fd);
    EXPECT_EQ(r.frame.flags & (CANFD_BRS | CANFD_ESI), CANFD_BRS);
    const std::string text = candump_log_text(kVcan, r.frame, r.is_fd);
    EXPECT_TRUE(text == "vcan0 345##1A0A1A2A3A4A5A6A7A8A9AAAB" ||
                text == "vcan0 345##5A0A1A2A3A4A5A6A7A8A9AAAB")
        << text;
    expected.push_back(text);
  }

  const CommandResult dumped = candump->finish();
  EXPECT_EQ(dumped.exit_status, 0) << dumped.output;
  const std::vector<LogLine> lines = parse_log(dumped.output);
  ASSERT_EQ(lines.size(), expected.size()) << dumped.output;
  for (std::size_t i = 0; i < lines.size(); ++i) EXPECT_EQ(lines[i].frame, expected[i]);
}

TEST_F(CanUtilsOnVcan, CansendToCandumpEndToEnd) {
  auto candump = start_candump("-L -n 1 -T 60000 vcan0,7E8:7FF");
  ASSERT_EQ(run_command("cansend vcan0 7E0#0201").exit_status, 0);
  ASSERT_EQ(run_command("cansend vcan0 7E8#064100BE3EB811").exit_status, 0);
  const CommandResult dumped = candump->finish();
  EXPECT_EQ(dumped.exit_status, 0) << dumped.output;
  const std::vector<LogLine> lines = parse_log(dumped.output);
  ASSERT_EQ(lines.size(), 1u) << dumped.output;
  EXPECT_EQ(lines[0].frame, "vcan0 7E8#064100BE3EB811");
  EXPECT_FALSE(lines[0].timestamp.empty());
}

}  // namespace
}  // namespace wavebench::vcan_smoke
