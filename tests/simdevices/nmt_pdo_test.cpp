// NMT state machine, heartbeat states, SYNC-driven TPDOs and PDO remapping by SDO.
#include <gtest/gtest.h>

#include "bench_fixture.hpp"

namespace wavebench::simdevices::testing {
namespace {

using NmtPdoTest = BenchFixture;

std::uint32_t u32(const can::Frame& f, std::size_t at) {
  return static_cast<std::uint32_t>(f.data[at] | (f.data[at + 1] << 8) | (f.data[at + 2] << 16) |
                                    (static_cast<std::uint32_t>(f.data[at + 3]) << 24));
}

TEST_F(NmtPdoTest, TransitionsShowInTheHeartbeat) {
  exchange(0x601, {0x2B, 0x17, 0x10, 0x00, 0x64, 0x00, 0, 0});  // 100 ms
  received.clear();
  advance(0.1);
  ASSERT_EQ(frames_with_id(0x701).size(), 1u);
  EXPECT_EQ(frames_with_id(0x701).back(), frame(0x701, {0x7F}));

  send(0x000, {0x01, 0x01});  // start node 1
  EXPECT_EQ(bench->drive().nmt_state(), NmtState::kOperational);
  EXPECT_EQ(bench->encoder().nmt_state(), NmtState::kPreOperational);
  advance(0.1);
  EXPECT_EQ(frames_with_id(0x701).back(), frame(0x701, {0x05}));

  send(0x000, {0x02, 0x00});  // stop all
  advance(0.1);
  EXPECT_EQ(frames_with_id(0x701).back(), frame(0x701, {0x04}));
  EXPECT_EQ(bench->encoder().nmt_state(), NmtState::kStopped);
  // Stopped: no SDO.
  EXPECT_TRUE(exchange(0x601, {0x40, 0x00, 0x10, 0x00, 0, 0, 0, 0}).empty());

  send(0x000, {0x80, 0x01});  // pre-operational
  advance(0.1);
  EXPECT_EQ(frames_with_id(0x701).back(), frame(0x701, {0x7F}));
  EXPECT_EQ(exchange(0x601, {0x40, 0x00, 0x10, 0x00, 0, 0, 0, 0}).size(), 1u);
}

TEST_F(NmtPdoTest, ResetCommunicationRestoresCommunicationObjectsAndBootsAgain) {
  exchange(0x601, {0x2B, 0x17, 0x10, 0x00, 0x64, 0x00, 0, 0});
  send(0x000, {0x01, 0x01});
  auto r = exchange(0x000, {0x82, 0x01});
  ASSERT_EQ(r.size(), 1u);
  EXPECT_EQ(r[0], frame(0x701, {0x00}));
  EXPECT_EQ(bench->drive().nmt_state(), NmtState::kPreOperational);
  EXPECT_EQ(bench->drive().od().get<std::uint16_t>(0x1017, 0), 0u);
  received.clear();
  advance(1.0);
  EXPECT_TRUE(frames_with_id(0x701).empty());  // heartbeat off again
}

TEST_F(NmtPdoTest, ResetNodeToAllBootsEveryNode) {
  const auto r = exchange(0x000, {0x81, 0x00});
  ASSERT_EQ(r.size(), 3u);
  EXPECT_EQ(r[0], frame(0x701, {0x00}));
  EXPECT_EQ(r[1], frame(0x703, {0x00}));
  EXPECT_EQ(r[2], frame(0x704, {0x00}));
}

TEST_F(NmtPdoTest, NmtForAnotherNodeIsIgnored) {
  send(0x000, {0x01, 0x05});
  EXPECT_EQ(bench->drive().nmt_state(), NmtState::kPreOperational);
}

TEST_F(NmtPdoTest, TpdosOnlyInOperationalAndOnEverySync) {
  EXPECT_TRUE(exchange(0x080, {}).empty());  // pre-operational: no PDOs
  send(0x000, {0x01, 0x00});
  const auto r = exchange(0x080, {});
  // Drive TPDO1 + TPDO2, encoder TPDO1, torque sensor TPDO1.
  ASSERT_EQ(r.size(), 4u);
  EXPECT_EQ(r[0].id, 0x181u);
  EXPECT_EQ(r[0].len, 6);
  EXPECT_EQ(r[1].id, 0x281u);
  EXPECT_EQ(r[1].len, 6);
  EXPECT_EQ(r[2].id, 0x183u);
  EXPECT_EQ(r[2].len, 4);
  EXPECT_EQ(u32(r[2], 0), bench->encoder().position_value());
  EXPECT_EQ(r[3].id, 0x184u);
  EXPECT_EQ(r[3].len, 4);
  // Statusword of the drive in switch-on disabled, remote.
  EXPECT_EQ(r[0].data[0] & 0x4F, 0x40);
}

TEST_F(NmtPdoTest, SyncDrivenClockAdvancesOneCyclePerSync) {
  bench->stop();
  bench.reset();
  config.clock = BenchClock::kSyncDriven;
  bench = std::make_unique<SimulatedBench>(config, *device_side);
  bench->start();
  send(0x000, {0x01, 0x00});
  exchange(0x601, {0x23, 0x06, 0x10, 0x00, 0xF4, 0x01, 0x00, 0x00});  // 500 us
  for (int i = 0; i < 10; ++i) send(0x080, {});
  EXPECT_NEAR(bench->now(), 10 * 500e-6, 1e-12);
}

TEST_F(NmtPdoTest, RemapTpdoInTheStandardOrderThenFramesCarryTheMappedBytes) {
  // Encoder TPDO1: position value (32 bit) then alarms (16 bit).
  const std::pair<std::array<std::uint8_t, 8>, const char*> steps[] = {
      {{0x23, 0x00, 0x18, 0x01, 0x83, 0x01, 0x00, 0x80}, "COB-ID invalid"},
      {{0x2F, 0x00, 0x1A, 0x00, 0x00, 0, 0, 0}, "sub0 = 0"},
      {{0x23, 0x00, 0x1A, 0x01, 0x20, 0x00, 0x04, 0x60}, "entry 1"},
      {{0x23, 0x00, 0x1A, 0x02, 0x10, 0x00, 0x03, 0x65}, "entry 2"},
      {{0x2F, 0x00, 0x1A, 0x00, 0x02, 0, 0, 0}, "sub0 = 2"},
      {{0x23, 0x00, 0x18, 0x01, 0x83, 0x01, 0x00, 0x00}, "COB-ID valid"},
  };
  for (const auto& [bytes, what] : steps) {
    SCOPED_TRACE(what);
    received.clear();
    master->send(can::Frame::make(0x603, bytes));
    io.poll();
    io.restart();
    const auto r = received;
    ASSERT_EQ(r.size(), 1u);
    EXPECT_EQ(r[0].data[0], 0x60);
  }
  send(0x000, {0x01, 0x03});
  const auto r = exchange(0x080, {});
  ASSERT_EQ(r.size(), 1u);
  ASSERT_EQ(r[0].id, 0x183u);
  ASSERT_EQ(r[0].len, 6);
  const std::uint32_t pos = bench->encoder().position_value();
  EXPECT_EQ(r[0], frame(0x183, {static_cast<std::uint8_t>(pos), static_cast<std::uint8_t>(pos >> 8),
                                static_cast<std::uint8_t>(pos >> 16),
                                static_cast<std::uint8_t>(pos >> 24), 0x00, 0x00}));
}

TEST_F(NmtPdoTest, MappingRefusedWhileValidAndBadEntriesRefused) {
  // PDO valid: neither sub0 nor entries may change (06090030).
  auto r = exchange(0x603, {0x2F, 0x00, 0x1A, 0x00, 0x00, 0, 0, 0});
  EXPECT_EQ(r.at(0), frame(0x583, {0x80, 0x00, 0x1A, 0x00, 0x30, 0x00, 0x09, 0x06}));
  r = exchange(0x603, {0x23, 0x00, 0x1A, 0x01, 0x20, 0x00, 0x04, 0x60});
  EXPECT_EQ(r.at(0), frame(0x583, {0x80, 0x00, 0x1A, 0x01, 0x30, 0x00, 0x09, 0x06}));
  // COB-ID change while valid is refused too.
  r = exchange(0x603, {0x23, 0x00, 0x18, 0x01, 0x90, 0x01, 0x00, 0x00});
  EXPECT_EQ(r.at(0), frame(0x583, {0x80, 0x00, 0x18, 0x01, 0x30, 0x00, 0x09, 0x06}));

  exchange(0x603, {0x23, 0x00, 0x18, 0x01, 0x83, 0x01, 0x00, 0x80});
  // Entries while sub0 != 0 are refused.
  r = exchange(0x603, {0x23, 0x00, 0x1A, 0x01, 0x20, 0x00, 0x04, 0x60});
  EXPECT_EQ(r.at(0), frame(0x583, {0x80, 0x00, 0x1A, 0x01, 0x30, 0x00, 0x09, 0x06}));
  exchange(0x603, {0x2F, 0x00, 0x1A, 0x00, 0x00, 0, 0, 0});
  // Not mappable (device type), no such object, wrong length.
  r = exchange(0x603, {0x23, 0x00, 0x1A, 0x01, 0x20, 0x00, 0x00, 0x10});
  EXPECT_EQ(r.at(0), frame(0x583, {0x80, 0x00, 0x1A, 0x01, 0x41, 0x00, 0x04, 0x06}));
  r = exchange(0x603, {0x23, 0x00, 0x1A, 0x01, 0x20, 0x00, 0x77, 0x67});
  EXPECT_EQ(r.at(0), frame(0x583, {0x80, 0x00, 0x1A, 0x01, 0x00, 0x00, 0x02, 0x06}));
  r = exchange(0x603, {0x23, 0x00, 0x1A, 0x01, 0x10, 0x00, 0x04, 0x60});
  EXPECT_EQ(r.at(0), frame(0x583, {0x80, 0x00, 0x1A, 0x01, 0x41, 0x00, 0x04, 0x06}));
  // Three 32-bit entries exceed 64 bits: refused at sub0 (06040042).
  for (std::uint8_t sub = 1; sub <= 3; ++sub) {
    r = exchange(0x603, {0x23, 0x00, 0x1A, sub, 0x20, 0x00, 0x04, 0x60});
    EXPECT_EQ(r.at(0).data[0], 0x60);
  }
  r = exchange(0x603, {0x2F, 0x00, 0x1A, 0x00, 0x03, 0, 0, 0});
  EXPECT_EQ(r.at(0), frame(0x583, {0x80, 0x00, 0x1A, 0x00, 0x42, 0x00, 0x04, 0x06}));
  // More than 8 entries is out of range.
  r = exchange(0x603, {0x2F, 0x00, 0x1A, 0x00, 0x09, 0, 0, 0});
  EXPECT_EQ(r.at(0), frame(0x583, {0x80, 0x00, 0x1A, 0x00, 0x30, 0x00, 0x09, 0x06}));
}

TEST_F(NmtPdoTest, RpdoControlwordActsImmediatelyWithType255) {
  send(0x000, {0x01, 0x01});
  send(0x201, {0x06, 0x00});
  EXPECT_EQ(bench->drive().state(), Cia402State::kReadyToSwitchOn);
  // Too short: EMCY 0x8210 and no change.
  const auto r = exchange(0x201, {0x07});
  EXPECT_EQ(bench->drive().state(), Cia402State::kReadyToSwitchOn);
  ASSERT_EQ(r.size(), 1u);
  EXPECT_EQ(r[0], frame(0x081, {0x10, 0x82, 0x11, 0, 0, 0, 0, 0}));
}

TEST_F(NmtPdoTest, SynchronousRpdoWaitsForSync) {
  // RPDO2 (controlword + target position) valid with transmission type 1.
  exchange(0x601, {0x23, 0x01, 0x14, 0x01, 0x01, 0x03, 0x00, 0x00});
  send(0x000, {0x01, 0x01});
  send(0x301, {0x06, 0x00, 0x10, 0x00, 0x00, 0x00});
  EXPECT_EQ(bench->drive().state(), Cia402State::kSwitchOnDisabled);
  EXPECT_EQ(bench->drive().od().get<std::int32_t>(0x607A, 0), 0);
  send(0x080, {});
  EXPECT_EQ(bench->drive().state(), Cia402State::kReadyToSwitchOn);
  EXPECT_EQ(bench->drive().od().get<std::int32_t>(0x607A, 0), 0x10);
}

}  // namespace
}  // namespace wavebench::simdevices::testing
