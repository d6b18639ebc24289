// Byte-exact SDO conversations against a scripted server on the virtual bus.
#include "wavebench/canopen/sdo_client.hpp"

#include <gtest/gtest.h>

#include "scripted_peer.hpp"

namespace wavebench::canopen {
namespace {

using testing::F;
using testing::ScriptedPeer;
using Strings = std::vector<std::string>;

struct SdoFixture : ::testing::Test {
  boost::asio::io_context io;
  can::VirtualCanBus bus{io};
  std::unique_ptr<can::VirtualCanEndpoint> master = bus.endpoint("master");
  ScriptedPeer peer{bus};
  SdoClient sdo{*master, 1, std::chrono::milliseconds(50)};
};

TEST_F(SdoFixture, ExpeditedUploadOfIdentityVendorId) {
  peer.expect("601#4018100100000000", {"581#4318100178563412"});
  EXPECT_EQ(sdo.read<std::uint32_t>(0x1018, 1), 0x12345678U);
  EXPECT_TRUE(peer.done());
  EXPECT_EQ(peer.received(), Strings{"601#4018100100000000"});
}

TEST_F(SdoFixture, ExpeditedDownloadOfHeartbeatTime4000ms) {
  peer.expect("601#2B171000A00F0000", {"581#6017100000000000"});
  sdo.write<std::uint16_t>(0x1017, 0, 4000);
  EXPECT_TRUE(peer.done());
  EXPECT_EQ(peer.received(), Strings{"601#2B171000A00F0000"});
}

TEST_F(SdoFixture, ExpeditedDownloadCommandPerSize) {
  peer.expect("601#2F00200011000000", {"581#6000200000000000"});
  peer.expect("601#2B00200011220000", {"581#6000200000000000"});
  peer.expect("601#2700200011223300", {"581#6000200000000000"});
  peer.expect("601#2300200011223344", {"581#6000200000000000"});
  const std::vector<std::uint8_t> bytes = {0x11, 0x22, 0x33, 0x44};
  for (std::size_t n = 1; n <= 4; ++n) sdo.download(0x2000, 0, {bytes.data(), n});
  EXPECT_TRUE(peer.done());
}

TEST_F(SdoFixture, SegmentedUploadOfDeviceName) {
  // "wavebench drive" (15 bytes): size-indicated initiate, then 7 + 7 + 1 bytes; the last
  // segment (toggle 0, 6 bytes unused, c = 1 -> 0x0D) comes as a short frame.
  peer.expect("601#4008100000000000", {"581#410810000F000000"});
  peer.expect("601#6000000000000000", {"581#007761766562656E"});
  peer.expect("601#7000000000000000", {"581#1063682064726976"});
  peer.expect("601#6000000000000000", {"581#0D65"});
  const auto data = sdo.upload(0x1008, 0);
  EXPECT_EQ(std::string(data.begin(), data.end()), "wavebench drive");
  EXPECT_TRUE(peer.done());
  EXPECT_EQ(peer.received(), (Strings{"601#4008100000000000", "601#6000000000000000",
                                      "601#7000000000000000", "601#6000000000000000"}));
}

TEST_F(SdoFixture, SegmentedUploadShorterThanIndicatedIsAborted) {
  peer.expect("601#4008100000000000", {"581#4108100010000000"});
  peer.expect("601#6000000000000000", {"581#0D65"});
  std::error_code ec;
  sdo.upload(0x1008, 0, ec);
  EXPECT_EQ(ec, make_error_code(SdoAbort::length_too_low));
}

TEST_F(SdoFixture, SegmentedDownloadOfTenBytes) {
  peer.expect("601#210120000A000000", {"581#6001200000000000"});
  peer.expect("601#0030313233343536", {"581#2000000000000000"});
  peer.expect("601#1937383900000000", {"581#3000000000000000"});
  const std::string text = "0123456789";
  sdo.download(0x2001, 0, std::span(reinterpret_cast<const std::uint8_t*>(text.data()), 10));
  EXPECT_TRUE(peer.done());
  EXPECT_EQ(peer.received(),
            (Strings{"601#210120000A000000", "601#0030313233343536", "601#1937383900000000"}));
}

TEST_F(SdoFixture, LongSegmentedUploadAlternatesToggle) {
  std::string expected;
  peer.expect("601#4000300000000000", {"581#4000300000000000"});  // size not indicated
  for (int i = 0; i < 40; ++i) {
    const bool toggle = i % 2 == 1;
    const bool last = i == 39;
    char request[32];
    std::snprintf(request, sizeof request, "601#%02X00000000000000", toggle ? 0x70 : 0x60);
    char reply[32];
    const int cmd = (toggle ? 0x10 : 0) | (last ? 1 : 0);
    std::snprintf(reply, sizeof reply, "581#%02X41424344454647", cmd);
    peer.expect(request, {reply});
    expected += "ABCDEFG";
  }
  const auto data = sdo.upload(0x3000, 0);
  EXPECT_EQ(std::string(data.begin(), data.end()), expected);
  EXPECT_TRUE(peer.done());
}

TEST_F(SdoFixture, ServerAbortBecomesErrorCodeAndException) {
  peer.expect("601#4000600000000000", {"581#8000600000000206"});
  std::error_code ec;
  const auto data = sdo.upload(0x6000, 0, ec);
  EXPECT_TRUE(data.empty());
  EXPECT_EQ(ec, make_error_code(SdoAbort::no_object));
  EXPECT_EQ(ec.message(), "06020000 object does not exist in the object dictionary");
  peer.expect("601#2F00600000000000", {"581#8000600002000106"});
  try {
    sdo.write<std::uint8_t>(0x6000, 0, 0);
    FAIL() << "no exception";
  } catch (const SdoError& e) {
    EXPECT_EQ(e.code(), make_error_code(SdoAbort::read_only));
    EXPECT_EQ(e.index(), 0x6000);
    EXPECT_NE(std::string(e.what()).find("06010002"), std::string::npos) << e.what();
  }
}

TEST_F(SdoFixture, TimeoutSendsAbortFrame) {
  std::error_code ec;
  sdo.upload(0x1018, 1, ec);
  EXPECT_EQ(ec, make_error_code(SdoAbort::timeout));
  io.restart();
  io.poll();
  EXPECT_EQ(peer.received(), (Strings{"601#4018100100000000", "601#8018100100000405"}));
}

TEST_F(SdoFixture, ToggleErrorAbortsWith05030000) {
  peer.expect("601#4008100000000000", {"581#4108100014000000"});
  peer.expect("601#6000000000000000", {"581#1041424344454647"});  // wrong toggle
  std::error_code ec;
  sdo.upload(0x1008, 0, ec);
  EXPECT_EQ(ec, make_error_code(SdoAbort::toggle_bit));
  io.restart();
  io.poll();
  EXPECT_EQ(peer.received().back(), "601#8008100000000305");
}

TEST_F(SdoFixture, ShortExpeditedReplyIsAccepted) {
  peer.expect("601#4000610100000000", {"581#4F00610105"});
  EXPECT_EQ(sdo.read<std::uint8_t>(0x6100, 1), 5);
}

TEST_F(SdoFixture, WrongSizeForTypedReadIsLengthMismatch) {
  peer.expect("601#4000610100000000", {"581#4F00610105000000"});
  std::error_code ec;
  sdo.read<std::uint32_t>(0x6100, 1, ec);
  EXPECT_EQ(ec, make_error_code(SdoAbort::length_mismatch));
}

TEST_F(SdoFixture, UnknownServerCommandIsAbortedAsInvalid) {
  peer.expect("601#4000610100000000", {"581#E000610100000000"});
  std::error_code ec;
  sdo.upload(0x6100, 1, ec);
  EXPECT_EQ(ec, make_error_code(SdoAbort::invalid_command));
  io.restart();
  io.poll();
  EXPECT_EQ(peer.received().back(), "601#8000610101000405");
}

TEST_F(SdoFixture, RequestsQueueAndCompleteInOrder) {
  peer.expect("601#4000100000000000", {"581#4300100092010200"});
  peer.expect("601#4001100000000000", {"581#4F01100000000000"});
  std::vector<int> order;
  sdo.async_upload(0x1000, 0, [&](std::error_code ec, std::vector<std::uint8_t> d) {
    EXPECT_FALSE(ec);
    EXPECT_EQ(d.size(), 4U);
    order.push_back(1);
  });
  sdo.async_upload(0x1001, 0, [&](std::error_code ec, std::vector<std::uint8_t> d) {
    EXPECT_FALSE(ec);
    EXPECT_EQ(d.size(), 1U);
    order.push_back(2);
  });
  io.run();
  EXPECT_EQ(order, (std::vector<int>{1, 2}));
}

TEST_F(SdoFixture, BlockUploadByteExact) {
  sdo.set_block_upload(true, 127);
  peer.expect("601#A00810007F000000", {"581#C20810000A000000"});
  peer.expect("601#A300000000000000",
              {"581#0130313233343536", "581#8237383900000000"});  // 7 + 3 bytes, last = seq 2
  peer.expect("601#A2027F0000000000", {"581#D100000000000000"});  // end: 4 bytes unused
  const auto data = sdo.upload(0x1008, 0);
  EXPECT_EQ(std::string(data.begin(), data.end()), "0123456789");
  io.restart();
  io.poll();
  EXPECT_TRUE(peer.done());
  EXPECT_EQ(peer.received().back(), "601#A100000000000000");
}

TEST_F(SdoFixture, BlockUploadAcksEveryBlock) {
  sdo.set_block_upload(true, 2);
  peer.expect("601#A008100002000000", {"581#C008100000000000"});  // size not indicated
  peer.expect("601#A300000000000000", {"581#0141414141414141", "581#0242424242424242"});
  peer.expect("601#A202020000000000", {"581#8143000000000000"});
  peer.expect("601#A201020000000000", {"581#D900000000000000"});  // 6 unused
  const auto data = sdo.upload(0x1008, 0);
  EXPECT_EQ(std::string(data.begin(), data.end()), "AAAAAAABBBBBBBC");
}

TEST_F(SdoFixture, BlockUploadFallsBackToSegmentedWhenUnsupported) {
  sdo.set_block_upload(true, 127);
  peer.expect("601#A00810007F000000", {"581#8008100001000405"});
  peer.expect("601#4008100000000000", {"581#4F08100041000000"});
  EXPECT_EQ(sdo.read<std::uint8_t>(0x1008, 0), 0x41);
}

TEST_F(SdoFixture, BlockUploadSequenceErrorIsAborted) {
  sdo.set_block_upload(true, 127);
  peer.expect("601#A00810007F000000", {"581#C20810000A000000"});
  peer.expect("601#A300000000000000", {"581#0230313233343536"});  // seq 2 first
  std::error_code ec;
  sdo.upload(0x1008, 0, ec);
  EXPECT_EQ(ec, make_error_code(SdoAbort::invalid_sequence));
  io.restart();
  io.poll();
  EXPECT_EQ(peer.received().back(), "601#8008100003000405");
}

TEST_F(SdoFixture, RepliesForOtherNodesAreIgnored) {
  peer.expect("601#4018100100000000", {"582#4318100100000000", "581#4318100101000000"});
  EXPECT_EQ(sdo.read<std::uint32_t>(0x1018, 1), 1U);
}

}  // namespace
}  // namespace wavebench::canopen
