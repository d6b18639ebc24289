#include <gtest/gtest.h>

#include <boost/asio/post.hpp>
#include <thread>

#include "scripted_peer.hpp"
#include "wavebench/canopen/emcy.hpp"
#include "wavebench/canopen/sync_producer.hpp"

namespace wavebench::canopen {
namespace {

using testing::F;
using testing::ScriptedPeer;

TEST(Sync, FramesWithAndWithoutCounter) {
  EXPECT_EQ(can::to_string(sync_frame()), "080#");
  EXPECT_EQ(can::to_string(sync_frame(7)), "080#07");
}

TEST(Sync, ProducerCountsWrapsAndKeepsAbsoluteDeadlines) {
  boost::asio::io_context io;
  can::VirtualCanBus bus(io);
  auto ep = bus.endpoint();
  ScriptedPeer peer(bus);
  SyncProducer sync(*ep, std::chrono::microseconds(1000), 3);
  std::vector<SyncProducer::Tick> ticks;
  sync.on_tick([&](const SyncProducer::Tick& t) {
    ticks.push_back(t);
    if (ticks.size() == 10) sync.stop();
  });
  sync.start();
  io.run();
  ASSERT_EQ(ticks.size(), 10U);
  std::vector<std::string> sent;
  for (const auto& f : bus.log()) sent.push_back(can::to_string(f));
  ASSERT_EQ(sent.size(), 10U);
  // Counter runs 1..3 per SYNC sent; a skipped period does not consume a counter value.
  for (std::size_t i = 0; i < 10; ++i) {
    EXPECT_EQ(ticks[i].counter, i % 3 + 1);
    EXPECT_EQ(sent[i], "080#0" + std::to_string(i % 3 + 1));
    if (i > 0) {
      EXPECT_GT(ticks[i].index, ticks[i - 1].index);
      // Deadlines sit on the grid t0 + k * period whatever the wakeup lateness.
      EXPECT_EQ((ticks[i].deadline - ticks[0].deadline) % std::chrono::microseconds(1000),
                std::chrono::steady_clock::duration::zero());
    }
    EXPECT_GE(ticks[i].sent, ticks[i].deadline);
  }
  EXPECT_EQ(sync.statistics().sent, 10U);
  EXPECT_EQ(ticks.back().index, 9U + sync.statistics().skipped);
}

TEST(Sync, LateWakeupIsReportedAndMissedPeriodsSkipped) {
  boost::asio::io_context io;
  can::VirtualCanBus bus(io);
  auto ep = bus.endpoint();
  SyncProducer sync(*ep, std::chrono::microseconds(1000));
  int late = 0;
  sync.on_late([&](const SyncProducer::Tick&, SyncProducer::Clock::duration) noexcept { ++late; },
               std::chrono::microseconds(500));
  int n = 0;
  sync.on_tick([&](const SyncProducer::Tick&) noexcept {
    // Block the io_context for five periods after the second tick: the third wakes late.
    if (++n == 2) {
      boost::asio::post(io, [] { std::this_thread::sleep_for(std::chrono::milliseconds(5)); });
    }
    if (n == 4) sync.stop();
  });
  sync.start();
  io.run();
  EXPECT_GE(late, 1);
  EXPECT_GE(sync.statistics().skipped, 3U);
  EXPECT_EQ(sync.statistics().sent, 4U);
  EXPECT_GE(sync.statistics().max_lateness, std::chrono::milliseconds(3));
}

TEST(Sync, BadParametersNameTheObject) {
  boost::asio::io_context io;
  can::VirtualCanBus bus(io);
  auto ep = bus.endpoint();
  try {
    SyncProducer s(*ep, std::chrono::microseconds(1000), 1);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("0x1019"), std::string::npos);
  }
  EXPECT_THROW(SyncProducer(*ep, std::chrono::microseconds(0)), std::invalid_argument);
}

TEST(Emcy, DecodeIsByteExact) {
  const auto e = decode_emcy(F("083#1023010102030405"));
  ASSERT_TRUE(e);
  EXPECT_EQ(e->node, 3);
  EXPECT_EQ(e->error_code, 0x2310);
  EXPECT_EQ(e->error_register, 0x01);
  EXPECT_EQ(e->vendor, (std::array<std::uint8_t, 5>{1, 2, 3, 4, 5}));
  EXPECT_EQ(can::to_string(emcy_frame(*e)), "083#1023010102030405");
  EXPECT_FALSE(decode_emcy(F("080#1023010102030405"))) << "0x080 is SYNC";
  EXPECT_FALSE(decode_emcy(F("083#10")));
  EXPECT_TRUE(decode_emcy(F("083#000000"))->is_reset());
  EXPECT_EQ(describe_emcy_code(0x2310), "2310 current");
  EXPECT_EQ(describe_emcy_code(0x8611), "8611 following error");
}

TEST(Emcy, ConsumerReportsEveryNodesEmergencies) {
  boost::asio::io_context io;
  can::VirtualCanBus bus(io);
  auto ep = bus.endpoint();
  ScriptedPeer peer(bus);
  std::vector<Emergency> seen;
  EmcyConsumer emcy(*ep, [&](const Emergency& e) noexcept { seen.push_back(e); });
  peer.send("081#1023010000000000");
  peer.send("080#");
  peer.send("181#1023010000000000");
  peer.send("0FF#0000000000000000");
  io.run();
  ASSERT_EQ(seen.size(), 2U);
  EXPECT_EQ(seen[0].node, 1);
  EXPECT_EQ(seen[1].node, 127);
  EXPECT_TRUE(seen[1].is_reset());
}

}  // namespace
}  // namespace wavebench::canopen
