#include "wavebench/canopen/cia402.hpp"

#include <gtest/gtest.h>

#include "fake_sdo_server.hpp"
#include "wavebench/canopen/cia402_drive.hpp"

namespace wavebench::canopen {
namespace {

using S = Cia402State;

ProfileMove move_to(std::int32_t target) {
  ProfileMove m;
  m.target = target;
  return m;
}

TEST(Cia402States, StatuswordMasksOfTheSpec) {
  EXPECT_EQ(decode_state(0x0000), S::not_ready_to_switch_on);
  EXPECT_EQ(decode_state(0x0040), S::switch_on_disabled);
  EXPECT_EQ(decode_state(0x0250), S::switch_on_disabled);  // remote, voltage, ignores bits 4-5
  EXPECT_EQ(decode_state(0x0021), S::ready_to_switch_on);
  EXPECT_EQ(decode_state(0x0031), S::ready_to_switch_on);
  EXPECT_EQ(decode_state(0x0023), S::switched_on);
  EXPECT_EQ(decode_state(0x0027), S::operation_enabled);
  EXPECT_EQ(decode_state(0x1637), S::operation_enabled);
  EXPECT_EQ(decode_state(0x0007), S::quick_stop_active);
  EXPECT_EQ(decode_state(0x000F), S::fault_reaction_active);
  EXPECT_EQ(decode_state(0x002F), S::fault_reaction_active);
  EXPECT_EQ(decode_state(0x0008), S::fault);
  EXPECT_EQ(decode_state(0x0228), S::fault);
  EXPECT_EQ(decode_state(0x0061), S::unknown);  // bit 6 with ready bits: no state
}

TEST(Cia402States, EveryTransitionHasItsControlword) {
  EXPECT_EQ(controlword_toward(S::switch_on_disabled, S::operation_enabled), 0x0006);   // 2
  EXPECT_EQ(controlword_toward(S::ready_to_switch_on, S::operation_enabled), 0x0007);   // 3
  EXPECT_EQ(controlword_toward(S::switched_on, S::operation_enabled), 0x000F);          // 4
  EXPECT_EQ(controlword_toward(S::operation_enabled, S::switched_on), 0x0007);          // 5
  EXPECT_EQ(controlword_toward(S::switched_on, S::ready_to_switch_on), 0x0006);         // 6
  EXPECT_EQ(controlword_toward(S::ready_to_switch_on, S::switch_on_disabled), 0x0000);  // 7
  EXPECT_EQ(controlword_toward(S::operation_enabled, S::ready_to_switch_on), 0x0006);   // 8
  EXPECT_EQ(controlword_toward(S::operation_enabled, S::switch_on_disabled), 0x0000);   // 9
  EXPECT_EQ(controlword_toward(S::switched_on, S::switch_on_disabled), 0x0000);         // 10
  EXPECT_EQ(controlword_toward(S::operation_enabled, S::quick_stop_active), 0x0002);    // 11
  EXPECT_EQ(controlword_toward(S::quick_stop_active, S::switch_on_disabled), 0x0000);   // 12
  EXPECT_EQ(controlword_toward(S::fault, S::operation_enabled), 0x0080);                // 15
  EXPECT_EQ(controlword_toward(S::quick_stop_active, S::operation_enabled), 0x000F);    // 16
  EXPECT_FALSE(controlword_toward(S::operation_enabled, S::operation_enabled));
  EXPECT_FALSE(controlword_toward(S::not_ready_to_switch_on, S::operation_enabled));
  EXPECT_FALSE(controlword_toward(S::fault_reaction_active, S::operation_enabled));
}

TEST(Cia402States, DescriptionsNameStateAndBits) {
  EXPECT_EQ(describe_statusword(0x0240), "switch on disabled (statusword 0x0240), voltage off");
  EXPECT_EQ(parse_operation_mode("csv"), OperationMode::cyclic_sync_velocity);
  EXPECT_FALSE(parse_operation_mode("xyz"));
}

// A CiA 402 device model written from the spec's tables for these tests only.
struct FakeDrive {
  testing::FakeSdoServer server;
  S state = S::switch_on_disabled;
  bool responsive = true;
  bool fault_clears = true;
  bool following_error = false;
  std::uint16_t last_cw = 0;
  std::int32_t position = 0;

  FakeDrive(can::VirtualCanBus& bus, std::uint8_t node) : server(bus, node) {
    server.set<std::uint16_t>(0x6040, 0, 0);
    server.set<std::uint16_t>(0x6041, 0, 0);
    server.set<std::uint16_t>(0x603F, 0, 0);
    server.set<std::int8_t>(0x6060, 0, 0);
    server.set<std::int8_t>(0x6061, 0, 0);
    server.set<std::int32_t>(0x607A, 0, 0);
    server.set<std::int32_t>(0x60FF, 0, 0);
    server.set<std::uint32_t>(0x6081, 0, 0);
    server.set<std::int32_t>(0x60F4, 0, 0);
    server.set<std::int32_t>(0x6064, 0, 0);
    publish();
    server.on_write = [this](std::uint16_t index, std::uint8_t,
                             const testing::FakeSdoServer::Bytes&) {
      if (index == 0x6060) server.set<std::int8_t>(0x6061, 0, server.get<std::int8_t>(0x6060, 0));
      if (index == 0x6040) controlword(server.get<std::uint16_t>(0x6040, 0));
    };
  }
  void fault(std::uint16_t code) {
    state = S::fault;
    server.set<std::uint16_t>(0x603F, 0, code);
    publish();
  }
  void controlword(std::uint16_t cw) {
    const bool rising7 = (cw & 0x80) && !(last_cw & 0x80);
    const bool rising4 = (cw & 0x10) && !(last_cw & 0x10);
    const bool falling4 = !(cw & 0x10) && (last_cw & 0x10);
    last_cw = cw;
    if (!responsive) return;
    const std::uint16_t c = cw & 0x8F;
    switch (state) {
      case S::switch_on_disabled:
        if ((c & 0x87) == 0x06) state = S::ready_to_switch_on;
        break;
      case S::ready_to_switch_on:
        if ((c & 0x8F) == 0x07 || (c & 0x8F) == 0x0F) state = S::switched_on;
        if ((c & 0x82) == 0x00 || (c & 0x86) == 0x02) state = S::switch_on_disabled;
        break;
      case S::switched_on:
        if ((c & 0x8F) == 0x0F) state = S::operation_enabled;
        if ((c & 0x87) == 0x06) state = S::ready_to_switch_on;
        if ((c & 0x82) == 0x00 || (c & 0x86) == 0x02) state = S::switch_on_disabled;
        break;
      case S::operation_enabled:
        if ((c & 0x8F) == 0x07) state = S::switched_on;
        if ((c & 0x87) == 0x06) state = S::ready_to_switch_on;
        if ((c & 0x82) == 0x00) state = S::switch_on_disabled;
        if ((c & 0x86) == 0x02) state = S::quick_stop_active;
        break;
      case S::quick_stop_active:
        if ((c & 0x82) == 0x00) state = S::switch_on_disabled;
        if ((c & 0x8F) == 0x0F) state = S::operation_enabled;
        break;
      case S::fault:
        if (rising7 && fault_clears) {
          state = S::switch_on_disabled;
          server.set<std::uint16_t>(0x603F, 0, 0);
        }
        break;
      default:
        break;
    }
    if (state == S::operation_enabled && server.get<std::int8_t>(0x6061, 0) == 1) {
      std::uint16_t sw_extra = extra;
      if (rising4) {
        sw_extra |= 0x1000;  // set-point acknowledge
        sw_extra &= static_cast<std::uint16_t>(~0x0400);
      }
      if (falling4) {
        sw_extra &= static_cast<std::uint16_t>(~0x1000);
        position = server.get<std::int32_t>(0x607A, 0);
        server.set<std::int32_t>(0x6064, 0, position);
        sw_extra |= following_error ? 0x2000 : 0x0400;
      }
      extra = sw_extra;
    }
    publish();
  }
  std::uint16_t extra = 0x0400;
  void publish() {
    std::uint16_t sw = 0;
    switch (state) {
      case S::not_ready_to_switch_on:
        sw = 0x0000;
        break;
      case S::switch_on_disabled:
        sw = 0x0040;
        break;
      case S::ready_to_switch_on:
        sw = 0x0031;
        break;
      case S::switched_on:
        sw = 0x0033;
        break;
      case S::operation_enabled:
        sw = static_cast<std::uint16_t>(0x0037 | extra);
        break;
      case S::quick_stop_active:
        sw = 0x0017;
        break;
      case S::fault_reaction_active:
        sw = 0x001F;
        break;
      case S::fault:
        sw = 0x0018;
        break;
      default:
        break;
    }
    server.set<std::uint16_t>(0x6041, 0, static_cast<std::uint16_t>(sw | 0x0200));
  }
  std::vector<std::uint16_t> controlwords() const {
    std::vector<std::uint16_t> out;
    for (const auto& [key, bytes] : server.writes) {
      if (key == 0x604000U) out.push_back(static_cast<std::uint16_t>(bytes[0] | bytes[1] << 8));
    }
    return out;
  }
};

struct DriveFixture : ::testing::Test {
  boost::asio::io_context io;
  can::VirtualCanBus bus{io};
  std::unique_ptr<can::VirtualCanEndpoint> master = bus.endpoint("master");
  FakeDrive fake{bus, 1};
  SdoClient sdo{*master, 1, std::chrono::milliseconds(200)};
  Cia402Drive drive{sdo,
                    Cia402Options{std::chrono::milliseconds(300), std::chrono::milliseconds(1), 3}};
};

TEST_F(DriveFixture, EnableWalksTransitions2To4) {
  drive.enable_operation();
  EXPECT_EQ(fake.state, S::operation_enabled);
  EXPECT_EQ(fake.controlwords(), (std::vector<std::uint16_t>{0x0006, 0x0007, 0x000F}));
}

TEST_F(DriveFixture, FaultResetUsesARisingEdgeThenEnables) {
  fake.fault(0x2310);
  fake.last_cw = 0x0080;  // bit 7 already high: a plain write of 0x80 would not be an edge
  drive.enable_operation();
  EXPECT_EQ(fake.state, S::operation_enabled);
  EXPECT_EQ(fake.controlwords(),
            (std::vector<std::uint16_t>{0x0000, 0x0080, 0x0006, 0x0007, 0x000F}));
}

TEST_F(DriveFixture, PersistentFaultIsReportedWithItsErrorCode) {
  fake.fault(0x7305);
  fake.fault_clears = false;
  std::error_code ec;
  drive.enable_operation(ec);
  EXPECT_EQ(ec, make_error_code(Cia402Errc::fault));
  EXPECT_EQ(drive.last_failure().state, S::fault);
  EXPECT_EQ(drive.last_failure().error_code, 0x7305);
  EXPECT_NE(drive.last_failure().message.find("0x7305"), std::string::npos)
      << drive.last_failure().message;
}

TEST_F(DriveFixture, StuckDriveSaysWhereItIsStuck) {
  fake.responsive = false;
  fake.server.set<std::uint16_t>(0x603F, 0, 0x3210);
  try {
    drive.enable_operation();
    FAIL() << "enabled a drive that ignores its controlword";
  } catch (const Cia402Error& e) {
    const std::string what = e.what();
    EXPECT_EQ(e.failure().state, S::switch_on_disabled);
    EXPECT_NE(what.find("stuck in switch on disabled"), std::string::npos) << what;
    EXPECT_NE(what.find("0x603F = 0x3210"), std::string::npos) << what;
  }
}

TEST_F(DriveFixture, QuickStopAndBackToDisabled) {
  drive.enable_operation();
  drive.quick_stop();
  EXPECT_EQ(fake.state, S::quick_stop_active);
  EXPECT_EQ(fake.controlwords().back(), 0x0002);
  drive.go_to(S::switch_on_disabled);
  EXPECT_EQ(fake.state, S::switch_on_disabled);
  EXPECT_EQ(fake.controlwords().back(), 0x0000);
}

TEST_F(DriveFixture, DisableTransitionsFromOperationEnabled) {
  drive.enable_operation();
  drive.go_to(S::switched_on);
  EXPECT_EQ(fake.controlwords().back(), 0x0007);  // 5
  drive.go_to(S::ready_to_switch_on);
  EXPECT_EQ(fake.controlwords().back(), 0x0006);  // 6
  drive.go_to(S::switch_on_disabled);
  EXPECT_EQ(fake.controlwords().back(), 0x0000);  // 7
}

TEST_F(DriveFixture, ProfilePositionNewSetPointHandshake) {
  drive.set_mode(OperationMode::profile_position);
  EXPECT_EQ(fake.server.get<std::int8_t>(0x6060, 0), 1);
  drive.enable_operation();
  drive.move(ProfileMove{123456, 1000, std::nullopt, std::nullopt, false, true});
  drive.wait_target_reached(std::chrono::milliseconds(300));
  EXPECT_EQ(fake.position, 123456);
  EXPECT_EQ(fake.server.get<std::uint32_t>(0x6081, 0), 1000U);
  const auto cws = fake.controlwords();
  ASSERT_GE(cws.size(), 6U);
  // ... 0x000F (enable), 0x002F (set-point staged), 0x003F (new set-point), 0x002F (released).
  EXPECT_EQ((std::vector<std::uint16_t>(cws.end() - 3, cws.end())),
            (std::vector<std::uint16_t>{0x002F, 0x003F, 0x002F}));
}

TEST_F(DriveFixture, FollowingErrorFailsTheMove) {
  fake.following_error = true;
  fake.server.set<std::int32_t>(0x60F4, 0, 70000);
  drive.set_mode(OperationMode::profile_position);
  drive.enable_operation();
  drive.move(move_to(1000));
  std::error_code ec;
  drive.wait_target_reached(std::chrono::milliseconds(300), ec);
  EXPECT_EQ(ec, make_error_code(Cia402Errc::following_error));
  EXPECT_NE(drive.last_failure().message.find("70000"), std::string::npos);
}

TEST_F(DriveFixture, MoveRefusedWhenNotEnabled) {
  std::error_code ec;
  drive.move(move_to(1000), ec);
  EXPECT_EQ(ec, make_error_code(Cia402Errc::not_enabled));
}

TEST_F(DriveFixture, VelocityModesWriteTheirTargets) {
  drive.set_mode(OperationMode::profile_velocity);
  drive.enable_operation();
  drive.set_target_velocity(-2500);
  EXPECT_EQ(fake.server.get<std::int32_t>(0x60FF, 0), -2500);
  drive.set_mode(OperationMode::cyclic_sync_velocity);
  EXPECT_EQ(fake.server.get<std::int8_t>(0x6061, 0), 9);
  drive.set_mode(OperationMode::cyclic_sync_position);
  drive.set_target_position(42);
  EXPECT_EQ(fake.server.get<std::int32_t>(0x607A, 0), 42);
}

TEST_F(DriveFixture, ModeNotEchoedIsReported) {
  fake.server.on_write = nullptr;  // the fake never updates 0x6061
  std::error_code ec;
  drive.set_mode(OperationMode::cyclic_sync_position, ec);
  EXPECT_EQ(ec, make_error_code(Cia402Errc::mode_not_accepted));
}

}  // namespace
}  // namespace wavebench::canopen
