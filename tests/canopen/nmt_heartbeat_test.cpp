#include <gtest/gtest.h>

#include <boost/asio/steady_timer.hpp>
#include <chrono>
#include <thread>

#include "scripted_peer.hpp"
#include "wavebench/canopen/heartbeat_consumer.hpp"
#include "wavebench/canopen/nmt.hpp"

namespace wavebench::canopen {
namespace {

using testing::F;
using testing::ScriptedPeer;
using Strings = std::vector<std::string>;

TEST(Nmt, CommandFramesAreByteExact) {
  EXPECT_EQ(can::to_string(nmt_frame(NmtCommand::start, 1)), "000#0101");
  EXPECT_EQ(can::to_string(nmt_frame(NmtCommand::stop, 3)), "000#0203");
  EXPECT_EQ(can::to_string(nmt_frame(NmtCommand::enter_preoperational, 4)), "000#8004");
  EXPECT_EQ(can::to_string(nmt_frame(NmtCommand::reset_node, 0)), "000#8100");
  EXPECT_EQ(can::to_string(nmt_frame(NmtCommand::reset_communication, 127)), "000#827F");
  EXPECT_THROW(nmt_frame(NmtCommand::start, 128), std::invalid_argument);
}

TEST(Nmt, MasterSendsOnTheBus) {
  boost::asio::io_context io;
  can::VirtualCanBus bus(io);
  auto ep = bus.endpoint();
  ScriptedPeer peer(bus);
  NmtMaster nmt(*ep);
  nmt.send(NmtCommand::start, 0);
  nmt.send(NmtCommand::reset_communication, 5);
  io.run();
  EXPECT_EQ(peer.received(), (Strings{"000#0100", "000#8205"}));
}

TEST(Nmt, CliSpellingsParse) {
  EXPECT_EQ(parse_nmt_command("preop"), NmtCommand::enter_preoperational);
  EXPECT_EQ(parse_nmt_command("reset-comm"), NmtCommand::reset_communication);
  EXPECT_FALSE(parse_nmt_command("go"));
}

TEST(Heartbeat, DecodeAndEncode) {
  const auto hb = decode_heartbeat(F("703#05"));
  ASSERT_TRUE(hb);
  EXPECT_EQ(hb->node, 3);
  EXPECT_EQ(hb->state, NmtState::operational);
  EXPECT_EQ(decode_heartbeat(F("701#00"))->state, NmtState::boot_up);
  EXPECT_EQ(decode_heartbeat(F("77F#7F"))->state, NmtState::preoperational);
  EXPECT_FALSE(decode_heartbeat(F("701#06")));
  EXPECT_FALSE(decode_heartbeat(F("701#0500")));
  EXPECT_FALSE(decode_heartbeat(F("700#05")));
  EXPECT_FALSE(decode_heartbeat(F("601#05")));
  EXPECT_EQ(can::to_string(heartbeat_frame(4, NmtState::stopped)), "704#04");
}

struct HeartbeatFixture : ::testing::Test {
  boost::asio::io_context io;
  can::VirtualCanBus bus{io};
  std::unique_ptr<can::VirtualCanEndpoint> master = bus.endpoint("master");
  ScriptedPeer node{bus};
  std::vector<std::string> events;
  HeartbeatConsumer consumer{
      *master, 2, std::chrono::milliseconds(40),
      HeartbeatConsumer::Hooks{
          [this](NodeId n, NmtState s) {
            events.push_back(std::to_string(n) + " " + std::string(to_string(s)));
          },
          [this](NodeId n) { events.push_back(std::to_string(n) + " lost"); },
          [this](NodeId n) { events.push_back(std::to_string(n) + " back"); }}};
};

TEST_F(HeartbeatFixture, NotArmedUntilTheFirstHeartbeat) {
  io.run_for(std::chrono::milliseconds(120));
  EXPECT_FALSE(consumer.armed());
  EXPECT_TRUE(events.empty());
}

TEST_F(HeartbeatFixture, LostHeartbeatRaisesTimeoutOnceThenRecovers) {
  // From before the heartbeats were sent: the consumer time runs from their arrival, however
  // long the loop takes to return after reading them.
  const auto start = std::chrono::steady_clock::now();
  node.send("702#00");
  node.send("702#7F");
  io.run_for(std::chrono::milliseconds(5));
  EXPECT_TRUE(consumer.armed());
  std::chrono::steady_clock::duration lost_after{};
  while (!consumer.timed_out() &&
         std::chrono::steady_clock::now() - start < std::chrono::seconds(5)) {
    io.run_one_for(std::chrono::milliseconds(10));
  }
  lost_after = std::chrono::steady_clock::now() - start;
  EXPECT_TRUE(consumer.timed_out());
  EXPECT_GE(lost_after, std::chrono::milliseconds(30)) << "never before the consumer time";
  io.restart();
  io.run_for(std::chrono::milliseconds(100));
  node.send("702#05");
  io.restart();
  io.run_for(std::chrono::milliseconds(5));
  EXPECT_EQ(events, (std::vector<std::string>{"2 boot-up", "2 pre-operational", "2 lost", "2 back",
                                              "2 operational"}));
}

TEST_F(HeartbeatFixture, RegularHeartbeatsNeverTimeOut) {
  int lost = 0;
  HeartbeatConsumer patient(*master, 5, std::chrono::seconds(5),
                            {nullptr, [&](NodeId) noexcept { ++lost; }, nullptr});
  node.send("705#05");
  for (int i = 0; i < 10; ++i) {
    io.run_for(std::chrono::milliseconds(10));
    node.send("705#05");
  }
  io.run_for(std::chrono::milliseconds(5));
  EXPECT_FALSE(patient.timed_out());
  EXPECT_EQ(lost, 0);
  EXPECT_EQ(patient.heartbeats(), 11U);
}

TEST_F(HeartbeatFixture, OtherNodesHeartbeatsDoNotArm) {
  node.send("703#05");
  io.run_for(std::chrono::milliseconds(5));
  EXPECT_FALSE(consumer.armed());
}

// Judged by arrival: a consumer on a loop that is held (post-run work on its thread) with a
// backlog of frames, as SocketCAN delivers them with their kernel receive timestamps.
struct HeartbeatByArrival : ::testing::Test {
  using SystemClock = std::chrono::system_clock;
  static constexpr auto kConsumerTime = std::chrono::milliseconds(200);

  // A heartbeat as the bus received it at `at`.
  void send_received_at(const char* candump, SystemClock::time_point at) {
    auto frame = testing::F(candump);
    frame.timestamp = at;
    node->send(frame);
  }

  boost::asio::io_context io;
  can::VirtualCanBus bus{io};
  std::unique_ptr<can::VirtualCanEndpoint> master = bus.endpoint("master");
  std::unique_ptr<can::VirtualCanEndpoint> node = bus.endpoint("node 2");
  std::vector<std::string> events;
  HeartbeatConsumer consumer{
      *master, 2, kConsumerTime,
      HeartbeatConsumer::Hooks{nullptr, [this](NodeId) { events.push_back("lost"); },
                               [this](NodeId) { events.push_back("back"); }}};
};

TEST_F(HeartbeatByArrival, AHeartbeatThatArrivedInTimeIsNotLostBecauseTheLoopReadItLate) {
  const auto t0 = SystemClock::now();
  send_received_at("702#05", t0);
  io.poll();
  ASSERT_TRUE(consumer.armed());
  // Due after the consumer's deadline, this handler runs after the consumer's timer handler
  // when the held loop turns again, and hands over the heartbeat that arrived at t0 + 190 ms
  // and waited unread behind other frames.
  boost::asio::steady_timer backlog(io);
  backlog.expires_after(std::chrono::milliseconds(250));
  backlog.async_wait([&](const boost::system::error_code&) {
    send_received_at("702#05", t0 + std::chrono::milliseconds(190));
  });
  std::this_thread::sleep_for(std::chrono::milliseconds(320));  // the loop is held
  io.restart();
  io.poll();
  EXPECT_EQ(consumer.heartbeats(), 2U);
  EXPECT_GE(consumer.late_verdicts_deferred(), 1U) << "the timer did not run late first";
  EXPECT_TRUE(events.empty()) << events.front();
  EXPECT_FALSE(consumer.timed_out());
}

TEST_F(HeartbeatByArrival, ASilentNodeIsStillLostAfterAHeldLoop) {
  send_received_at("702#05", SystemClock::now());
  io.poll();
  std::this_thread::sleep_for(std::chrono::milliseconds(320));  // the loop is held
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(5);
  while (!consumer.timed_out() && std::chrono::steady_clock::now() < deadline) {
    io.restart();
    io.run_one_for(std::chrono::milliseconds(10));
  }
  EXPECT_TRUE(consumer.timed_out());
  EXPECT_EQ(events, (std::vector<std::string>{"lost"}));
}

TEST_F(HeartbeatByArrival, HeartbeatsTooFarApartAreALossEvenWhenReadTogether) {
  const auto now = SystemClock::now();
  send_received_at("702#05", now - std::chrono::milliseconds(300));
  send_received_at("702#05", now);
  io.poll();
  EXPECT_EQ(consumer.heartbeats(), 2U);
  EXPECT_EQ(events, (std::vector<std::string>{"lost", "back"}));
  EXPECT_FALSE(consumer.timed_out());
}

}  // namespace
}  // namespace wavebench::canopen
