// The CiA 402 drive: state machine walk through controlword/statusword, faults with EMCY and
// the fault-reset edge, a PP move with the new-set-point handshake and target reached, PV.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "bench_fixture.hpp"

namespace wavebench::simdevices::testing {
namespace {

class Cia402DriveTest : public BenchFixture {
 protected:
  void write_u16(std::uint16_t index, std::uint16_t value) {
    const auto r = exchange(
        0x601, {0x2B, static_cast<std::uint8_t>(index), static_cast<std::uint8_t>(index >> 8), 0x00,
                static_cast<std::uint8_t>(value), static_cast<std::uint8_t>(value >> 8), 0, 0});
    ASSERT_FALSE(r.empty());
    ASSERT_EQ(r.back().data[0], 0x60) << "write of 0x" << std::hex << index << " refused";
  }
  void write_i32(std::uint16_t index, std::int32_t value) {
    const auto v = static_cast<std::uint32_t>(value);
    const auto r = exchange(
        0x601, {0x23, static_cast<std::uint8_t>(index), static_cast<std::uint8_t>(index >> 8), 0x00,
                static_cast<std::uint8_t>(v), static_cast<std::uint8_t>(v >> 8),
                static_cast<std::uint8_t>(v >> 16), static_cast<std::uint8_t>(v >> 24)});
    ASSERT_FALSE(r.empty());
    ASSERT_EQ(r.back().data[0], 0x60);
  }
  void write_i8(std::uint16_t index, std::int8_t value) {
    const auto r = exchange(
        0x601, {0x2F, static_cast<std::uint8_t>(index), static_cast<std::uint8_t>(index >> 8), 0x00,
                static_cast<std::uint8_t>(value), 0, 0, 0});
    ASSERT_FALSE(r.empty());
    ASSERT_EQ(r.back().data[0], 0x60);
  }
  // The statusword as an SDO upload returns it.
  std::uint16_t statusword() {
    const auto r = exchange(0x601, {0x40, 0x41, 0x60, 0x00, 0, 0, 0, 0});
    EXPECT_EQ(r.size(), 1u);
    EXPECT_EQ(r.at(0).data[0], 0x4B);
    return static_cast<std::uint16_t>(r.at(0).data[4] | (r.at(0).data[5] << 8));
  }
  std::int32_t read_i32(std::uint16_t index) {
    const auto r = exchange(0x601, {0x40, static_cast<std::uint8_t>(index),
                                    static_cast<std::uint8_t>(index >> 8), 0x00, 0, 0, 0, 0});
    EXPECT_EQ(r.at(0).data[0], 0x43);
    return static_cast<std::int32_t>(r.at(0).data[4] | (r.at(0).data[5] << 8) |
                                     (r.at(0).data[6] << 16) |
                                     (static_cast<std::uint32_t>(r.at(0).data[7]) << 24));
  }
  void enable() {
    write_u16(0x6040, 0x0006);
    write_u16(0x6040, 0x0007);
    write_u16(0x6040, 0x000F);
    ASSERT_EQ(statusword() & 0x6F, 0x27);
  }
};

TEST_F(Cia402DriveTest, StateMachineWalk) {
  EXPECT_EQ(statusword() & 0x4F, 0x40);  // switch on disabled
  write_u16(0x6040, 0x0006);             // shutdown
  EXPECT_EQ(statusword() & 0x6F, 0x21);  // ready to switch on
  write_u16(0x6040, 0x0007);             // switch on
  EXPECT_EQ(statusword() & 0x6F, 0x23);  // switched on
  write_u16(0x6040, 0x000F);             // enable operation
  EXPECT_EQ(statusword() & 0x6F, 0x27);  // operation enabled
  write_u16(0x6040, 0x0002);             // quick stop
  EXPECT_EQ(statusword() & 0x6F, 0x07);  // quick stop active
  advance(0.05);
  EXPECT_EQ(statusword() & 0x6F, 0x07);  // option code 6: stays after the stop
  write_u16(0x6040, 0x0000);             // disable voltage
  EXPECT_EQ(statusword() & 0x4F, 0x40);
  // Switch on without shutdown first is not a transition from switch on disabled.
  write_u16(0x6040, 0x0007);
  EXPECT_EQ(statusword() & 0x4F, 0x40);
}

TEST_F(Cia402DriveTest, QuickStopOptionTwoEndsInSwitchOnDisabled) {
  write_u16(0x605A, 2);
  enable();
  write_u16(0x6040, 0x0002);
  advance(0.05);
  EXPECT_EQ(statusword() & 0x4F, 0x40);
}

// The bench's quick stop on a trip: controlword 0x0002 in RPDO1 (event-driven by default),
// taken on reception, no SYNC needed.
TEST_F(Cia402DriveTest, QuickStopInRpdoOneActsOnReception) {
  send(0x000, {0x01, 0x01});
  enable();
  send(0x201, {0x02, 0x00});
  EXPECT_EQ(bench->drive().state(), Cia402State::kQuickStopActive);
  EXPECT_EQ(statusword() & 0x6F, 0x07);
}

// NMT stop, the bench's fallback when a quick stop goes unconfirmed: the drive reacts as its
// abort connection option code 0x6007 says (2 by default: power stage off at once).
TEST_F(Cia402DriveTest, NmtStopAppliesTheAbortConnectionOption) {
  EXPECT_EQ(bench->drive().od().get<std::int16_t>(0x6007, 0), 2);
  struct Case {
    std::uint16_t option;
    Cia402State after;
  };
  for (const auto& c :
       {Case{0, Cia402State::kOperationEnabled}, Case{1, Cia402State::kFault},
        Case{2, Cia402State::kSwitchOnDisabled}, Case{3, Cia402State::kQuickStopActive}}) {
    send(0x000, {0x81, 0x01});  // reset node: defaults, switch on disabled
    send(0x000, {0x01, 0x01});
    write_u16(0x6007, c.option);
    enable();
    send(0x000, {0x02, 0x01});
    EXPECT_EQ(bench->drive().nmt_state(), NmtState::kStopped);
    advance(0.001);
    EXPECT_EQ(bench->drive().state(), c.after)
        << "option " << c.option << ": " << to_string(bench->drive().state());
  }
  // Out of the code's range: refused like any value out of range.
  send(0x000, {0x01, 0x01});
  const auto r = exchange(0x601, {0x2B, 0x07, 0x60, 0x00, 4, 0, 0, 0});
  ASSERT_EQ(r.size(), 1u);
  EXPECT_EQ(r[0].data[0], 0x80);
}

TEST_F(Cia402DriveTest, FaultSendsEmcyAndNeedsAResetEdge) {
  send(0x000, {0x01, 0x01});
  enable();
  received.clear();
  write_u16(0x2F00, 0x7121);  // inject "motor blocked"
  const auto emcy = frames_with_id(0x081);
  ASSERT_EQ(emcy.size(), 1u);
  EXPECT_EQ(emcy[0], frame(0x081, {0x21, 0x71, 0x01, 0, 0, 0, 0, 0}));
  advance(0.001);
  EXPECT_EQ(statusword() & 0x4F, 0x08);  // fault
  EXPECT_EQ(bench->drive().od().get<std::uint16_t>(0x603F, 0), 0x7121);
  EXPECT_EQ(bench->drive().od().get<std::uint8_t>(0x1001, 0), 0x01);

  write_u16(0x6040, 0x0080);  // rising edge of bit 7
  EXPECT_EQ(statusword() & 0x4F, 0x40);
  write_u16(0x2F00, 0x2310);  // over-current: error register bit 1 too
  EXPECT_EQ(frames_with_id(0x081).back(), frame(0x081, {0x10, 0x23, 0x03, 0, 0, 0, 0, 0}));
  advance(0.001);
  write_u16(0x6040, 0x0080);  // still high: no edge, stays in fault
  EXPECT_EQ(statusword() & 0x4F, 0x08);
  write_u16(0x6040, 0x0000);
  EXPECT_EQ(statusword() & 0x4F, 0x08);
  write_u16(0x6040, 0x0080);  // rising edge (write_u16 keeps what this exchange brought)
  ASSERT_EQ(frames_with_id(0x081).size(), 1u);
  EXPECT_EQ(frames_with_id(0x081)[0], frame(0x081, {0, 0, 0, 0, 0, 0, 0, 0}));  // error reset
  EXPECT_EQ(statusword() & 0x4F, 0x40);
  EXPECT_EQ(bench->drive().od().get<std::uint16_t>(0x603F, 0), 0u);
}

TEST_F(Cia402DriveTest, ProfilePositionMoveReachesTargetWithHandshake) {
  write_i8(0x6060, 1);
  EXPECT_EQ(bench->drive().od().get<std::int8_t>(0x6061, 0), 1);
  enable();
  const std::int32_t target = 5 * 131072;  // five motor revolutions
  write_i32(0x607A, target);
  write_u16(0x6040, 0x001F);  // new set-point
  std::uint16_t sw = statusword();
  EXPECT_TRUE(sw & 0x1000) << "set-point acknowledge";
  EXPECT_FALSE(sw & 0x0400) << "target reached before moving";
  write_u16(0x6040, 0x000F);
  EXPECT_FALSE(statusword() & 0x1000);
  advance(0.1);
  EXPECT_FALSE(statusword() & 0x0400) << "still moving";
  bool reached = false;
  for (int i = 0; i < 300 && !reached; ++i) {
    advance(0.01);
    reached = statusword() & 0x0400;
  }
  ASSERT_TRUE(reached);
  EXPECT_NEAR(read_i32(0x6064), target, 20);
  EXPECT_EQ(statusword() & 0x6F, 0x27);
  // The output followed through the gear: 5/N of a turn, within the TE of the unit (a few
  // arcmin and its offset).
  const double out_turns = bench->encoder().position_value() / static_cast<double>(1 << 20);
  const double ratio = bench->plant().ratio();
  EXPECT_NEAR(out_turns * 360 * 60, 5.0 / ratio * 360 * 60, 8.0);  // arcmin
}

TEST_F(Cia402DriveTest, RelativeMoveAndSetPointBuffer) {
  write_i8(0x6060, 1);
  enable();
  write_i32(0x607A, 131072);
  write_u16(0x6040, 0x001F);
  write_u16(0x6040, 0x000F);
  write_i32(0x607A, 131072);
  write_u16(0x6040, 0x005F);  // relative to the last target, buffered behind the first
  EXPECT_TRUE(statusword() & 0x1000);
  write_u16(0x6040, 0x004F);
  EXPECT_TRUE(statusword() & 0x1000) << "buffer full keeps the acknowledge";
  bool reached = false;
  for (int i = 0; i < 300 && !reached; ++i) {
    advance(0.01);
    reached = (statusword() & 0x0400) && !(statusword() & 0x1000);
  }
  ASSERT_TRUE(reached);
  EXPECT_NEAR(read_i32(0x6064), 2 * 131072, 20);
}

TEST_F(Cia402DriveTest, ProfileVelocityReachesSpeed) {
  write_i8(0x6060, 3);
  enable();
  const std::int32_t speed = 131072 * 100 / 60;  // 100 rpm
  write_i32(0x60FF, speed);
  advance(0.5);
  EXPECT_TRUE(statusword() & 0x0400);
  EXPECT_NEAR(read_i32(0x606C), speed, 0.01 * speed);
  const double omega = bench->plant().state().omega_in;
  EXPECT_NEAR(omega, 100.0 / 60 * 2 * std::numbers::pi, 0.02);
}

TEST_F(Cia402DriveTest, FollowingErrorFaults) {
  write_i8(0x6060, 1);
  write_i32(0x6065, 100);  // a tiny window
  write_u16(0x6066, 1);    // 1 ms
  write_u16(0x6072, 10);   // 1 % torque: cannot follow
  bench->set_brake_torque(50);
  enable();
  write_i32(0x607A, 10 * 131072);
  write_u16(0x6040, 0x001F);
  received.clear();
  advance(0.5);
  ASSERT_FALSE(frames_with_id(0x081).empty());
  EXPECT_EQ(frames_with_id(0x081)[0], frame(0x081, {0x11, 0x86, 0x21, 0, 0, 0, 0, 0}));
  EXPECT_EQ(statusword() & 0x4F, 0x08);
  EXPECT_EQ(bench->drive().od().get<std::uint16_t>(0x603F, 0), 0x8611);
}

TEST_F(Cia402DriveTest, UnsupportedModeIsRefused) {
  const auto r = exchange(0x601, {0x2F, 0x60, 0x60, 0x00, 0x06, 0, 0, 0});  // homing
  ASSERT_EQ(r.size(), 1u);
  EXPECT_EQ(r[0], frame(0x581, {0x80, 0x60, 0x60, 0x00, 0x30, 0x00, 0x09, 0x06}));
}

}  // namespace
}  // namespace wavebench::simdevices::testing

namespace wavebench::simdevices::testing {
namespace {

class CyclicSyncTest : public BenchFixture {
 protected:
  CyclicSyncTest() : BenchFixture(BenchClock::kSyncDriven) {}
};

TEST_F(CyclicSyncTest, CspFollowsTargetsSentByRpdoOnEverySync) {
  exchange(0x601, {0x23, 0x01, 0x14, 0x01, 0x01, 0x03, 0x00, 0x00});  // RPDO2 valid
  exchange(0x601, {0x2F, 0x60, 0x60, 0x00, 0x08, 0, 0, 0});           // CSP
  send(0x000, {0x01, 0x01});
  std::int32_t target = 0;
  const std::uint16_t cws[] = {0x06, 0x07, 0x0F};
  for (const auto cw : cws) {
    send(0x301, {static_cast<std::uint8_t>(cw), 0, 0, 0, 0, 0});
    send(0x080, {});
  }
  EXPECT_EQ(bench->drive().state(), Cia402State::kOperationEnabled);
  for (int i = 0; i < 300; ++i) {
    target += 200;  // 200 increments per 1 ms cycle
    const auto t = static_cast<std::uint32_t>(target);
    send(0x301, {0x0F, 0x00, static_cast<std::uint8_t>(t), static_cast<std::uint8_t>(t >> 8),
                 static_cast<std::uint8_t>(t >> 16), static_cast<std::uint8_t>(t >> 24)});
    send(0x080, {});
  }
  const auto moving_error = bench->drive().od().get<std::int32_t>(0x60F4, 0);
  EXPECT_LT(std::abs(moving_error), 400);  // velocity feed-forward keeps the lag small
  for (int i = 0; i < 100; ++i) send(0x080, {});
  EXPECT_NEAR(bench->drive().od().get<std::int32_t>(0x6064, 0), target, 20);
  EXPECT_EQ(bench->drive().statusword() & 0x1000, 0x1000);  // following the target
  EXPECT_NEAR(bench->now(), 403e-3, 1e-9);
}

}  // namespace
}  // namespace wavebench::simdevices::testing
