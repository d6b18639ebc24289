#include "wavebench/can/frame.hpp"

#include <gtest/gtest.h>

namespace wavebench::can {
namespace {

TEST(Frame, MakeSetsLengthDataAndStandardId) {
  const auto f = Frame::make(0x601, {0x40, 0x18, 0x10, 0x01});
  EXPECT_EQ(f.id, 0x601U);
  EXPECT_FALSE(f.extended);
  EXPECT_EQ(f.len, 4);
  EXPECT_EQ(f.data[0], 0x40);
  EXPECT_EQ(f.data[3], 0x01);
  EXPECT_EQ(f.raw_id(), 0x601U);
}

TEST(Frame, IdAboveElevenBitsIsExtended) {
  const auto f = Frame::make(0x1ABCDEF0, {});
  EXPECT_TRUE(f.extended);
  EXPECT_EQ(f.raw_id(), 0x1ABCDEF0U | kExtendedFlag);
}

TEST(Frame, MoreThanEightBytesIsRejected) {
  const std::uint8_t nine[9] = {};
  EXPECT_THROW(Frame::make(0x100, std::span<const std::uint8_t>(nine, 9)), std::invalid_argument);
}

TEST(Frame, EqualityIgnoresTimestampAndUnusedBytes) {
  auto a = Frame::make(0x181, {1, 2});
  auto b = a;
  b.timestamp = std::chrono::system_clock::now();
  b.data[5] = 0xFF;
  EXPECT_EQ(a, b);
  b.data[1] = 3;
  EXPECT_NE(a, b);
}

TEST(Frame, CandumpFormatRoundTrips) {
  EXPECT_EQ(to_string(Frame::make(0x601, {0x40, 0x18, 0x10, 0x01, 0, 0, 0, 0})),
            "601#4018100100000000");
  EXPECT_EQ(to_string(Frame::make(0x080, {})), "080#");
  auto ext = Frame::make(0x12345678, {0xAB});
  EXPECT_EQ(to_string(ext), "12345678#AB");
  Frame rtr;
  rtr.id = 0x701;
  rtr.rtr = true;
  rtr.len = 1;
  EXPECT_EQ(to_string(rtr), "701#R1");
  for (const char* text : {"601#4018100100000000", "080#", "12345678#AB", "701#R1", "123#R"}) {
    const auto parsed = parse_frame(text);
    ASSERT_TRUE(parsed) << text;
    EXPECT_EQ(to_string(*parsed), text);
  }
  const auto dotted = parse_frame("123#11.22.33");
  ASSERT_TRUE(dotted);
  EXPECT_EQ(dotted->len, 3);
  EXPECT_EQ(dotted->data[2], 0x33);
}

TEST(Frame, MalformedTextIsRejected) {
  for (const char* text : {"", "601", "6012#00", "800#00", "601#0", "601#000102030405060708",
                           "60G#00", "601#R9", "601#ZZ"}) {
    EXPECT_FALSE(parse_frame(text)) << text;
  }
}

}  // namespace
}  // namespace wavebench::can
