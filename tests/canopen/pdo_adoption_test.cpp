// A PDO whose mapping cannot be written is read back and used as found (issue 20).
#include "wavebench/canopen/pdo_adoption.hpp"

#include <gtest/gtest.h>

#include "fake_sdo_server.hpp"
#include "scripted_peer.hpp"
#include "wavebench/canopen/sdo_abort.hpp"
#include "wavebench/canopen/sdo_client.hpp"

namespace wavebench::canopen {
namespace {

using testing::F;
using testing::FakeSdoServer;
using testing::ScriptedPeer;

const NeededObject kDriveNeeds[] = {
    {0x6041, 0, 16, "statusword"},
    {0x6064, 0, 32, "position actual value"},
    {0x606C, 0, 32, "velocity actual value"},
    {0x60F4, 0, 32, "following error actual value", true},
};

PdoAdoption fixed(unsigned number, std::vector<PdoEntry> entries, std::uint32_t cob = 0,
                  std::uint8_t type = 1) {
  return {PdoDirection::transmit, number,
          PdoConfig{cob ? cob : tpdo_cob_id(number, 1), type, 0, std::move(entries)}, true,
          make_error_code(SdoAbort::read_only)};
}

struct Bus {
  boost::asio::io_context io;
  can::VirtualCanBus bus{io};
  std::unique_ptr<can::VirtualCanEndpoint> ep = bus.endpoint();
  SdoClient sdo{*ep, 1, std::chrono::milliseconds(100)};
};

TEST(PdoAdoption, ReadOnlyTpdoIsReadBackByteExact) {
  Bus b;
  ScriptedPeer node(b.bus);
  // The bench's first remap write (COB-ID invalid) is refused: 06010002 read-only.
  node.expect("601#2300180181010080", {"581#8000180102000106"});
  // Read back: COB-ID 0x181 valid, type 1, two entries: position then statusword.
  node.expect("601#4000180100000000", {"581#4300180181010000"});
  node.expect("601#4000180200000000", {"581#4F00180201000000"});
  node.expect("601#40001A0000000000", {"581#4F001A0002000000"});
  node.expect("601#40001A0100000000", {"581#43001A0120006460"});
  node.expect("601#40001A0200000000", {"581#43001A0210004160"});
  const auto pdo = configure_or_read_back(
      b.sdo, PdoDirection::transmit, 1,
      PdoConfig{tpdo_cob_id(1, 1), 1, 0, {{0x6041, 0, 16}, {0x6064, 0, 32}}});
  EXPECT_TRUE(node.done());
  EXPECT_TRUE(pdo.fixed);
  EXPECT_EQ(pdo.refusal, make_error_code(SdoAbort::read_only));
  EXPECT_EQ(pdo.actual.cob_id, 0x181U);
  EXPECT_EQ(pdo.actual.transmission_type, 1);
  EXPECT_EQ(describe(pdo), "TPDO1 fixed [0x6064:0/32, 0x6041:0/16]");

  // Valid and synchronous already: nothing more is written.
  const auto used = use_tpdos(b.sdo, {pdo}, std::span(kDriveNeeds).first(2));
  EXPECT_EQ(node.received().size(), 6U);
  EXPECT_EQ(used.summary(), "fixed mapping, used as found: TPDO1 [0x6064:0/32, 0x6041:0/16]");
  const auto frame = F("181#785634F23700");
  EXPECT_EQ(used.raw(0, 0, frame), 0x0037U);
  EXPECT_EQ(used.signed_value(1, 0, frame), static_cast<std::int32_t>(0xF2345678U));
  EXPECT_FALSE(used.fits(0, F("181#7856341237")));
  EXPECT_FALSE(used.raw(0, 0, F("181#7856341237")));
}

TEST(PdoAdoption, OtherAbortsStayErrors) {
  Bus b;
  ScriptedPeer node(b.bus);
  node.expect("601#2300180181010080", {"581#8000180100000606"});  // 06060000 hardware error
  EXPECT_THROW(configure_or_read_back(b.sdo, PdoDirection::transmit, 1,
                                      PdoConfig{tpdo_cob_id(1, 1), 1, 0, {{0x6041, 0, 16}}}),
               std::system_error);
  for (auto abort : {SdoAbort::read_only, SdoAbort::invalid_value, SdoAbort::not_mappable,
                     SdoAbort::pdo_too_long, SdoAbort::data_transfer, SdoAbort::local_control,
                     SdoAbort::device_state})
    EXPECT_TRUE(is_fixed_mapping_refusal(make_error_code(abort)));
  EXPECT_FALSE(is_fixed_mapping_refusal(make_error_code(SdoAbort::timeout)));
  EXPECT_FALSE(is_fixed_mapping_refusal(make_error_code(SdoAbort::no_object)));
}

TEST(PdoAdoption, MissingStatuswordIsNamed) {
  Bus b;
  try {
    use_tpdos(b.sdo, {fixed(1, {{0x6064, 0, 32}}), fixed(2, {{0x606C, 0, 32}})}, kDriveNeeds);
    FAIL() << "expected a refusal";
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(),
                 "TPDO1 fixed [0x6064:0/32], TPDO2 fixed [0x606C:0/32]: 0x6041:0 statusword not "
                 "mapped in any TPDO");
  }
}

TEST(PdoAdoption, ValuesAreDecodedWhereverTheyAre) {
  Bus b;
  const NeededObject needs[] = {kDriveNeeds[2], kDriveNeeds[1], kDriveNeeds[0], kDriveNeeds[3]};
  // Velocity in TPDO1, position and statusword in TPDO2 on an unusual COB-ID; each behind a
  // 4-bit dummy entry, so at bit offsets 4 and 36.
  const auto used = use_tpdos(b.sdo,
                              {fixed(1, {{0x0005, 0, 4}, {0x606C, 0, 32}}),
                               fixed(2, {{0x0005, 0, 4}, {0x6064, 0, 32}, {0x6041, 0, 16}}, 0x1F0)},
                              needs);
  ASSERT_EQ(used.pdos().size(), 2U);
  EXPECT_EQ(used.configs()[1].cob_id, 0x1F0U);
  EXPECT_FALSE(used.has(3));  // 0x60F4 optional, absent
  can::Frame f1;
  f1.id = 0x181;
  f1.len = 5;
  insert_bits(std::span(f1.data), 4, 32, static_cast<std::uint32_t>(-1234));
  can::Frame f2;
  f2.id = 0x1F0;
  f2.len = 7;
  insert_bits(std::span(f2.data), 4, 32, static_cast<std::uint32_t>(-5));
  insert_bits(std::span(f2.data), 36, 16, 0x1637);
  EXPECT_EQ(used.signed_value(0, 0, f1), -1234);
  EXPECT_FALSE(used.signed_value(0, 1, f2));  // velocity is not in TPDO2
  EXPECT_EQ(used.signed_value(1, 1, f2), -5);
  EXPECT_EQ(used.raw(2, 1, f2), 0x1637U);
  EXPECT_EQ(used.summary(),
            "fixed mapping, used as found: TPDO1 [0x0005:0/4, 0x606C:0/32], TPDO2 [0x0005:0/4, "
            "0x6064:0/32, 0x6041:0/16]");
}

TEST(PdoAdoption, FixedPdoWithNothingNeededIsNotUsedAWrittenOneIs) {
  Bus b;
  PdoAdoption written{
      PdoDirection::transmit, 1, PdoConfig{0x181, 1, 0, {{0x6041, 0, 16}}}, false, {}};
  const NeededObject needs[] = {kDriveNeeds[0], kDriveNeeds[3]};
  const auto used = use_tpdos(b.sdo, {written, fixed(2, {{0x2000, 0, 8}})}, needs);
  ASSERT_EQ(used.pdos().size(), 1U);
  EXPECT_EQ(used.pdos()[0].number, 1U);
  EXPECT_FALSE(used.any_fixed());
  EXPECT_EQ(used.summary(), "");
}

TEST(PdoAdoption, FewerBitsThanTheTypeAreRefused) {
  Bus b;
  try {
    use_tpdos(b.sdo, {fixed(1, {{0x6041, 0, 16}, {0x6064, 0, 16}}), fixed(2, {{0x606C, 0, 32}})},
              kDriveNeeds);
    FAIL() << "expected a refusal";
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(),
                 "TPDO1 fixed [0x6041:0/16, 0x6064:0/16], TPDO2 fixed [0x606C:0/32]: 0x6064:0 "
                 "position actual value is mapped in TPDO1 with 16 bits: expected 32");
  }
  // Unless documented as allowed for that object.
  const NeededObject low_byte[] = {{0x6041, 0, 16, "statusword", false, 8}};
  EXPECT_NO_THROW(use_tpdos(b.sdo, {fixed(1, {{0x6041, 0, 8}})}, low_byte));
}

// The communication parameters may be writable where the mapping is not: the bench makes a used
// fixed PDO valid and synchronous, in the order CiA 301 allows (type while invalid).
TEST(PdoAdoption, DisabledEventDrivenPdoIsMadeSynchronousWhereItMayBe) {
  Bus b;
  FakeSdoServer node(b.bus, 1);
  node.set<std::uint32_t>(0x1801, 1, 0x80000281U);
  node.set<std::uint8_t>(0x1801, 2, 254);
  const auto used = use_tpdos(
      b.sdo,
      {fixed(1, {{0x6041, 0, 16}, {0x6064, 0, 32}}), fixed(2, {{0x606C, 0, 32}}, 0x80000281U, 254)},
      kDriveNeeds);
  ASSERT_EQ(node.writes.size(), 2U);
  EXPECT_EQ(node.get<std::uint8_t>(0x1801, 2), 1);
  EXPECT_EQ(node.get<std::uint32_t>(0x1801, 1), 0x281U);
  EXPECT_EQ(used.configs()[1].cob_id, 0x281U);
  EXPECT_EQ(used.configs()[1].transmission_type, 1);
}

TEST(PdoAdoption, UnwritableTransmissionTypeOrCobIdIsNamed) {
  Bus b;
  FakeSdoServer node(b.bus, 1);
  node.set<std::uint32_t>(0x1801, 1, 0x281U);
  node.set<std::uint8_t>(0x1801, 2, 2);
  node.refuse_write = [](std::uint16_t index, std::uint8_t sub) -> std::uint32_t {
    return index == 0x1801 && sub == 2 ? 0x06010002 : 0;
  };
  try {
    use_tpdos(b.sdo,
              {fixed(1, {{0x6041, 0, 16}, {0x6064, 0, 32}}), fixed(2, {{0x606C, 0, 32}}, 0x281, 2)},
              kDriveNeeds);
    FAIL() << "expected a refusal";
  } catch (const std::runtime_error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("TPDO2 fixed [0x606C:0/32] is transmission type 0x1801:2 = 2 (sent once "
                        "every 2 SYNCs, not on every SYNC) and it cannot be written (SDO abort "
                        "06010002"),
              std::string::npos)
        << what;
  }
  // The bench invalidated it to write the type: it is put back as it was.
  EXPECT_EQ(node.get<std::uint32_t>(0x1801, 1), 0x281U);

  node.refuse_write = [](std::uint16_t, std::uint8_t) -> std::uint32_t { return 0x06010002; };
  node.set<std::uint32_t>(0x1801, 1, 0x80000281U);
  try {
    use_tpdos(
        b.sdo,
        {fixed(1, {{0x6041, 0, 16}, {0x6064, 0, 32}}), fixed(2, {{0x606C, 0, 32}}, 0x80000281U, 1)},
        kDriveNeeds);
    FAIL() << "expected a refusal";
  } catch (const std::runtime_error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("TPDO2 fixed [0x606C:0/32] is disabled (COB-ID 0x1801:1 = 0x80000281, bit "
                        "31 set) and its COB-ID cannot be written"),
              std::string::npos)
        << what;
  }
}

}  // namespace
}  // namespace wavebench::canopen
