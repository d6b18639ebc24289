#include "wavebench/canopen/pdo.hpp"

#include <gtest/gtest.h>

#include "scripted_peer.hpp"
#include "wavebench/canopen/sdo_client.hpp"

namespace wavebench::canopen {
namespace {

using testing::F;
using testing::ScriptedPeer;
using Strings = std::vector<std::string>;

TEST(Pdo, MappingEntryEncoding) {
  EXPECT_EQ((PdoEntry{0x6004, 0, 32}).encode(), 0x60040020U);
  EXPECT_EQ((PdoEntry{0x6041, 0, 16}).encode(), 0x60410010U);
  const auto e = PdoEntry::decode(0x60640020U);
  EXPECT_EQ(e.index, 0x6064);
  EXPECT_EQ(e.sub, 0);
  EXPECT_EQ(e.bits, 32);
}

TEST(Pdo, RemapFollowsTheSpecOrderByteExact) {
  boost::asio::io_context io;
  can::VirtualCanBus bus(io);
  auto ep = bus.endpoint();
  ScriptedPeer node(bus);
  SdoClient sdo(*ep, 3, std::chrono::milliseconds(100));
  // TPDO1 of node 3: COB-ID 0x183 invalid, type 1, clear mapping, 0x6004:00/32, count 1, valid.
  node.expect("603#2300180183010080", {"583#6000180100000000"});
  node.expect("603#2F00180201000000", {"583#6000180200000000"});
  node.expect("603#2F001A0000000000", {"583#60001A0000000000"});
  node.expect("603#23001A0120000460", {"583#60001A0100000000"});
  node.expect("603#2F001A0001000000", {"583#60001A0000000000"});
  node.expect("603#2300180183010000", {"583#6000180100000000"});
  configure_pdo(sdo, PdoDirection::transmit, 1,
                PdoConfig{tpdo_cob_id(1, 3), 1, 0, {{0x6004, 0, 32}}});
  EXPECT_TRUE(node.done());
  EXPECT_EQ(node.received().size(), 6U);
}

TEST(Pdo, RemapStopsAtTheFirstAbort) {
  boost::asio::io_context io;
  can::VirtualCanBus bus(io);
  auto ep = bus.endpoint();
  ScriptedPeer node(bus);
  SdoClient sdo(*ep, 1, std::chrono::milliseconds(100));
  node.expect("601#2301140101030080", {"581#6001140100000000"});
  node.expect("601#2F01140201000000", {"581#6001140200000000"});
  node.expect("601#2F01160000000000", {"581#6001160000000000"});
  node.expect("601#2301160120000070", {"581#8001160141000406"});
  std::error_code ec;
  configure_pdo(sdo, PdoDirection::receive, 2,
                PdoConfig{rpdo_cob_id(2, 1), 1, 0, {{0x7000, 0, 32}}}, ec);
  EXPECT_EQ(ec, make_error_code(SdoAbort::not_mappable));
  EXPECT_EQ(node.received().size(), 4U);
  EXPECT_THROW(configure_pdo(sdo, PdoDirection::receive, 0, PdoConfig{}), std::system_error);
}

TEST(Pdo, LayoutPacksLittleEndianInMappingOrder) {
  PdoLayout layout({{0x6041, 0, 16}, {0x6064, 0, 32}, {0x6077, 0, 16}});
  EXPECT_EQ(layout.length_bytes(), 8U);
  const auto f = F("181#3700785634120CFE");
  ASSERT_TRUE(layout.fits(f));
  EXPECT_EQ(layout.raw(f, 0), 0x0037U);
  EXPECT_EQ(layout.raw(f, 1), 0x12345678U);
  EXPECT_EQ(layout.signed_value(f, 2), -500);
  const std::uint64_t values[] = {0x0037, 0x12345678, static_cast<std::uint16_t>(-500)};
  EXPECT_EQ(layout.make_frame(0x181, values), f);
  EXPECT_FALSE(layout.fits(F("181#370078563412")));
}

TEST(Pdo, BitFieldsAndFloats) {
  PdoLayout bits({{0x2000, 1, 1}, {0x2000, 2, 3}, {0x2000, 3, 4}, {0x2001, 0, 32}});
  can::Frame f;
  f.len = 5;
  bits.set_raw(f, 0, 1);
  bits.set_raw(f, 1, 5);
  bits.set_raw(f, 2, 0xA);
  bits.set_raw(f, 3, std::bit_cast<std::uint32_t>(1.5F));
  EXPECT_EQ(f.data[0], 0xAB);  // 1 | 5<<1 | 0xA<<4
  EXPECT_EQ(bits.raw(f, 1), 5U);
  EXPECT_FLOAT_EQ(bits.f32(f, 3), 1.5F);
  EXPECT_THROW(PdoLayout({{0x2000, 0, 64}, {0x2001, 0, 8}}), std::invalid_argument);
  EXPECT_THROW(PdoLayout({{0x2000, 0, 0}}), std::invalid_argument);
}

}  // namespace
}  // namespace wavebench::canopen
