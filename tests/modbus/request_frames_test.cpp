// The client's requests, byte for byte, against a scripted peer on a plain TCP socket: the
// frames come from the Modbus spec (MBAP header, function codes 3/4/6/16), not from libmodbus.
#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <thread>
#include <vector>

#include "brake_test_support.hpp"

namespace wavebench::testing {
namespace {

using Bytes = std::vector<uint8_t>;

// Accepts one connection; for each step reads exactly `request.size()` bytes, records them and
// answers with `reply`.
class ScriptedPeer {
 public:
  struct Step {
    Bytes request;
    Bytes reply;
  };
  explicit ScriptedPeer(std::vector<Step> steps) : steps_(std::move(steps)) {
    listen_ = socket(AF_INET, SOCK_STREAM, 0);
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    bind(listen_, reinterpret_cast<sockaddr*>(&a), sizeof a);
    listen(listen_, 1);
    socklen_t len = sizeof a;
    getsockname(listen_, reinterpret_cast<sockaddr*>(&a), &len);
    port_ = ntohs(a.sin_port);
    thread_ = std::thread([this] { run(); });
  }
  ~ScriptedPeer() {
    shutdown(listen_, SHUT_RDWR);
    ::close(listen_);
    thread_.join();
  }
  int port() const { return port_; }
  std::vector<Bytes> received;

 private:
  void run() {
    timeval tv{5, 0};
    const int c = accept(listen_, nullptr, nullptr);
    if (c < 0) return;
    setsockopt(c, SOL_SOCKET, SO_RCVTIMEO, &tv, sizeof tv);
    for (const auto& s : steps_) {
      Bytes got(s.request.size());
      size_t n = 0;
      while (n < got.size()) {
        const ssize_t r = recv(c, got.data() + n, got.size() - n, 0);
        if (r <= 0) break;
        n += static_cast<size_t>(r);
      }
      got.resize(n);
      received.push_back(got);
      if (n < s.request.size()) break;
      send(c, s.reply.data(), s.reply.size(), MSG_NOSIGNAL);
    }
    ::close(c);
  }
  std::vector<Step> steps_;
  int listen_;
  int port_;
  std::thread thread_;
};

TEST(RequestFrames, WatchdogHeartbeatAndReadbackAreExact) {
  // Input registers 0..20: status 0x0021, current 1.25 A (0x3FA00000), torque 62.5 (0x427A0000),
  // temperature 31.5 (0x41FC0000), slip power 12 W (0x41400000), alarm code 0.
  Bytes read_reply{0x00, 0x03, 0x00, 0x00, 0x00, 0x2D, 0x01, 0x04, 0x2A};
  const uint16_t regs[21] = {0x0021, 0,      0,      0,      0,      0,      0,
                             0,      0,      0,      0x3FA0, 0x0000, 0x427A, 0x0000,
                             0x41FC, 0x0000, 0x4140, 0x0000, 0,      0,      0};
  for (const uint16_t r : regs) {
    read_reply.push_back(static_cast<uint8_t>(r >> 8));
    read_reply.push_back(static_cast<uint8_t>(r & 0xFF));
  }
  const Bytes watchdog{0x00, 0x01, 0x00, 0x00, 0x00, 0x06, 0x01, 0x06, 0x00, 0x01, 0x01, 0xF4};
  const Bytes heartbeat{0x00, 0x02, 0x00, 0x00, 0x00, 0x06, 0x01, 0x06, 0x00, 0x02, 0x00, 0x01};
  const Bytes read_inputs{0x00, 0x03, 0x00, 0x00, 0x00, 0x06, 0x01, 0x04, 0x00, 0x00, 0x00, 0x15};
  // Setpoint ramp 0.5 (0x3F000000) to holding 12-13 with function 16.
  const Bytes read_control{0x00, 0x04, 0x00, 0x00, 0x00, 0x06, 0x01, 0x03, 0x00, 0x00, 0x00, 0x01};
  const Bytes control_reply{0x00, 0x04, 0x00, 0x00, 0x00, 0x05, 0x01, 0x03, 0x02, 0x00, 0x04};
  const Bytes write_control{0x00, 0x05, 0x00, 0x00, 0x00, 0x06, 0x01, 0x06, 0x00, 0x00, 0x00, 0x00};
  const Bytes write_ramp{0x00, 0x06, 0x00, 0x00, 0x00, 0x0B, 0x01, 0x10, 0x00,
                         0x0C, 0x00, 0x02, 0x04, 0x3F, 0x00, 0x00, 0x00};
  const Bytes ramp_reply{0x00, 0x06, 0x00, 0x00, 0x00, 0x06, 0x01, 0x10, 0x00, 0x0C, 0x00, 0x02};
  const Bytes write_setpoint{0x00, 0x07, 0x00, 0x00, 0x00, 0x0B, 0x01, 0x10, 0x00,
                             0x0A, 0x00, 0x02, 0x04, 0x3F, 0xC0, 0x00, 0x00};
  const Bytes setpoint_reply{0x00, 0x07, 0x00, 0x00, 0x00, 0x06,
                             0x01, 0x10, 0x00, 0x0A, 0x00, 0x02};
  ScriptedPeer peer({{watchdog, watchdog},
                     {heartbeat, heartbeat},
                     {read_inputs, read_reply},
                     {read_control, control_reply},
                     {write_control, write_control},
                     {write_ramp, ramp_reply},
                     {write_setpoint, setpoint_reply}});
  modbus::BrakeClient client(client_config_tcp(peer.port()));
  client.set_watchdog(500ms);
  client.heartbeat();
  const auto r = client.read();
  // Current mode from torque mode: control 0x0004 -> 0x0000.
  client.set_setpoint(1.5, modbus::BrakeMode::current, 0.5);
  ASSERT_EQ(peer.received.size(), 7u);
  EXPECT_EQ(peer.received[0], watchdog);
  EXPECT_EQ(peer.received[1], heartbeat);
  EXPECT_EQ(peer.received[2], read_inputs);
  EXPECT_EQ(peer.received[3], read_control);
  EXPECT_EQ(peer.received[4], write_control);
  EXPECT_EQ(peer.received[5], write_ramp);
  EXPECT_EQ(peer.received[6], write_setpoint);
  EXPECT_TRUE(r.status.output_on);
  EXPECT_TRUE(r.status.at_setpoint);
  EXPECT_FALSE(r.status.alarm);
  EXPECT_DOUBLE_EQ(r.coil_current_a, 1.25);
  EXPECT_DOUBLE_EQ(r.torque_nm, 62.5);
  EXPECT_DOUBLE_EQ(r.temperature_c, 31.5);
  EXPECT_DOUBLE_EQ(r.slip_power_w, 12.0);
}

TEST(RequestFrames, ReplyWithForeignTransactionIdIsRejected) {
  const Bytes heartbeat{0x00, 0x01, 0x00, 0x00, 0x00, 0x06, 0x01, 0x06, 0x00, 0x02, 0x00, 0x01};
  const Bytes stale{0x00, 0x09, 0x00, 0x00, 0x00, 0x06, 0x01, 0x06, 0x00, 0x02, 0x00, 0x01};
  ScriptedPeer peer({{heartbeat, stale}});
  modbus::BrakeClient client(client_config_tcp(peer.port()));
  try {
    client.heartbeat();
    ADD_FAILURE() << "stale reply accepted";
  } catch (const modbus::ModbusError& e) {
    EXPECT_EQ(e.kind(), modbus::ModbusErrorKind::bad_reply) << e.what();
    EXPECT_NE(std::string(e.what()).find("transaction id 9"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace wavebench::testing
