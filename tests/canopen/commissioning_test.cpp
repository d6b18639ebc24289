// What the `wavebench can` commands build on: value text, frame decoding, node scanning.
#include <gtest/gtest.h>

#include "fake_sdo_server.hpp"
#include "scripted_peer.hpp"
#include "wavebench/canopen/frame_description.hpp"
#include "wavebench/canopen/node_scanner.hpp"
#include "wavebench/canopen/value_text.hpp"

namespace wavebench::canopen {
namespace {

using testing::F;
using Bytes = std::vector<std::uint8_t>;

TEST(ValueText, EncodesEveryType) {
  EXPECT_EQ(encode_value("u8", "255"), (Bytes{0xFF}));
  EXPECT_EQ(encode_value("u16", "4000"), (Bytes{0xA0, 0x0F}));
  EXPECT_EQ(encode_value("u32", "0x12345678"), (Bytes{0x78, 0x56, 0x34, 0x12}));
  EXPECT_EQ(encode_value("u64", "1"), (Bytes{1, 0, 0, 0, 0, 0, 0, 0}));
  EXPECT_EQ(encode_value("i8", "-128"), (Bytes{0x80}));
  EXPECT_EQ(encode_value("i16", "-2"), (Bytes{0xFE, 0xFF}));
  EXPECT_EQ(encode_value("i32", "-1"), (Bytes{0xFF, 0xFF, 0xFF, 0xFF}));
  EXPECT_EQ(encode_value("i64", "-9223372036854775808"), (Bytes{0, 0, 0, 0, 0, 0, 0, 0x80}));
  EXPECT_EQ(encode_value("f32", "1.5"), (Bytes{0, 0, 0xC0, 0x3F}));
  EXPECT_EQ(encode_value("f64", "-2"), (Bytes{0, 0, 0, 0, 0, 0, 0, 0xC0}));
  EXPECT_EQ(encode_value("str", "ab"), (Bytes{'a', 'b'}));
  EXPECT_EQ(encode_value("hex", "de ad:BE.ef"), (Bytes{0xDE, 0xAD, 0xBE, 0xEF}));
}

TEST(ValueText, RejectsOutOfRangeAndNamesTheType) {
  for (auto [type, text] : std::vector<std::pair<const char*, const char*>>{{"u8", "256"},
                                                                            {"u8", "-1"},
                                                                            {"i8", "128"},
                                                                            {"u16", "x"},
                                                                            {"f32", "1.5x"},
                                                                            {"hex", "abc"},
                                                                            {"u32", ""}}) {
    try {
      encode_value(type, text);
      FAIL() << type << " " << text;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(type), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("expected"), std::string::npos) << e.what();
    }
  }
  EXPECT_THROW(encode_value("u24", "1"), std::invalid_argument);
}

TEST(ValueText, FormatsTypedAndUntyped) {
  EXPECT_EQ(format_value("i16", Bytes{0xFE, 0xFF}), "-2");
  EXPECT_EQ(format_value("u32", Bytes{0x78, 0x56, 0x34, 0x12}), "305419896");
  EXPECT_EQ(format_value("f32", Bytes{0, 0, 0xC0, 0x3F}), "1.5");
  EXPECT_EQ(format_value("str", Bytes{'h', 'i'}), "hi");
  EXPECT_EQ(format_value("hex", Bytes{1, 0xAB}), "01 AB");
  EXPECT_EQ(format_value("", Bytes{0x92, 0x01, 0x02, 0x00}), "0x00020192 (131474) [92 01 02 00]");
  EXPECT_EQ(format_value("", Bytes{'W', 'B', '-', 'S', 'I', 'M'}), "57 42 2D 53 49 4D \"WB-SIM\"");
  EXPECT_THROW(format_value("u32", Bytes{1, 2}), std::invalid_argument);
  EXPECT_EQ(parse_number("index", "0x1018", 0xFFFF), 0x1018U);
  EXPECT_EQ(parse_number("sub", "10", 0xFF), 10U);
  EXPECT_THROW(parse_number("sub", "256", 0xFF), std::invalid_argument);
}

TEST(FrameDescription, DecodesEveryService) {
  EXPECT_EQ(describe_frame(F("000#0101")), "000#0101  NMT start node 1");
  EXPECT_EQ(describe_frame(F("000#8200")), "000#8200  NMT reset-comm all nodes");
  EXPECT_EQ(describe_frame(F("080#")), "080#  SYNC");
  EXPECT_EQ(describe_frame(F("080#05")), "080#05  SYNC counter 5");
  EXPECT_EQ(describe_frame(F("083#1023010000000000")),
            "083#1023010000000000  EMCY node 3 2310 current register 0x01 [00 00 00 00 00]");
  EXPECT_EQ(describe_frame(F("181#3700")), "181#3700  TPDO1 node 1 [37 00]");
  EXPECT_EQ(describe_frame(F("501#01")), "501#01  RPDO4 node 1 [01]");
  EXPECT_EQ(describe_frame(F("601#4018100100000000")),
            "601#4018100100000000  SDO node 1 request initiate upload 1018:01");
  EXPECT_EQ(describe_frame(F("581#4318100178563412")),
            "581#4318100178563412  SDO node 1 response upload response 1018:01 expedited "
            "[78 56 34 12] = 0x12345678 (305419896) [78 56 34 12]");
  EXPECT_EQ(describe_frame(F("601#2B171000A00F0000")),
            "601#2B171000A00F0000  SDO node 1 request initiate download 1017:00 expedited [A0 0F]");
  EXPECT_EQ(describe_frame(F("581#8000600000000206")),
            "581#8000600000000206  SDO node 1 response abort 6000:00 06020000 object does not "
            "exist in the object dictionary");
  EXPECT_EQ(describe_frame(F("703#05")), "703#05  HEARTBEAT node 3 operational");
  EXPECT_EQ(describe_frame(F("701#00")), "701#00  HEARTBEAT node 1 boot-up");
  EXPECT_EQ(describe_frame(F("7E5#00")), "7E5#00  unassigned");
}

TEST(NodeScanner, FindsNodesTheirTypeIdentityAndHeartbeat) {
  boost::asio::io_context io;
  can::VirtualCanBus bus(io);
  auto master = bus.endpoint();
  testing::FakeSdoServer drive(bus, 1);
  drive.set<std::uint32_t>(0x1000, 0, 0x00020192);
  for (std::uint8_t s = 1; s <= 4; ++s) drive.set<std::uint32_t>(0x1018, s, 0xA570 + s);
  testing::FakeSdoServer encoder(bus, 3);
  encoder.set<std::uint32_t>(0x1000, 0, 0x00020196);
  encoder.set<std::uint32_t>(0x1018, 1, 0x1234);  // only the mandatory vendor id
  testing::ScriptedPeer hb(bus);
  hb.send("703#05");
  bus.record(false);
  const auto nodes = scan_nodes(*master, ScanOptions{std::chrono::milliseconds(30), 1, 127});
  ASSERT_EQ(nodes.size(), 2U);
  EXPECT_EQ(nodes[0].node, 1);
  EXPECT_EQ(nodes[0].device_type, 0x00020192U);
  EXPECT_EQ(nodes[0].identity[3], 0xA574U);
  EXPECT_FALSE(nodes[0].heartbeat_state);
  EXPECT_EQ(nodes[1].node, 3);
  EXPECT_EQ(nodes[1].device_type, 0x00020196U);
  EXPECT_EQ(nodes[1].identity[0], 0x1234U);
  EXPECT_FALSE(nodes[1].identity[1]);
  EXPECT_EQ(nodes[1].heartbeat_state, NmtState::operational);
}

}  // namespace
}  // namespace wavebench::canopen
