// The SDO server against byte-exact frames (CiA 301 §7.2.4) on the VirtualCanBus.
#include <gtest/gtest.h>

#include "bench_fixture.hpp"

namespace wavebench::simdevices::testing {
namespace {

using SdoServerTest = BenchFixture;

TEST_F(SdoServerTest, BootUpMessagesFromAllThreeNodes) {
  // start() already ran in SetUp; the boot-up frames are in `received`.
  ASSERT_EQ(received.size(), 3u);
  EXPECT_EQ(received[0], frame(0x701, {0x00}));
  EXPECT_EQ(received[1], frame(0x703, {0x00}));
  EXPECT_EQ(received[2], frame(0x704, {0x00}));
}

TEST_F(SdoServerTest, ExpeditedUploadOfDeviceTypes) {
  auto r = exchange(0x601, {0x40, 0x00, 0x10, 0x00, 0, 0, 0, 0});
  ASSERT_EQ(r.size(), 1u);
  EXPECT_EQ(r[0], frame(0x581, {0x43, 0x00, 0x10, 0x00, 0x92, 0x01, 0x02, 0x00}));
  r = exchange(0x603, {0x40, 0x00, 0x10, 0x00, 0, 0, 0, 0});
  ASSERT_EQ(r.size(), 1u);
  EXPECT_EQ(r[0], frame(0x583, {0x43, 0x00, 0x10, 0x00, 0x96, 0x01, 0x02, 0x00}));
  // One-byte object: 0x4F, unused bytes zero.
  r = exchange(0x601, {0x40, 0x18, 0x10, 0x00, 0, 0, 0, 0});
  ASSERT_EQ(r.size(), 1u);
  EXPECT_EQ(r[0], frame(0x581, {0x4F, 0x18, 0x10, 0x00, 0x04, 0x00, 0x00, 0x00}));
}

TEST_F(SdoServerTest, SegmentedUploadOfDeviceName) {
  // "WB-SIM servo drive" = 18 bytes: segments of 7, 7 and 4.
  auto r = exchange(0x601, {0x40, 0x08, 0x10, 0x00, 0, 0, 0, 0});
  ASSERT_EQ(r.size(), 1u);
  EXPECT_EQ(r[0], frame(0x581, {0x41, 0x08, 0x10, 0x00, 18, 0, 0, 0}));
  r = exchange(0x601, {0x60, 0, 0, 0, 0, 0, 0, 0});
  ASSERT_EQ(r.size(), 1u);
  EXPECT_EQ(r[0], frame(0x581, {0x00, 'W', 'B', '-', 'S', 'I', 'M', ' '}));
  r = exchange(0x601, {0x70, 0, 0, 0, 0, 0, 0, 0});
  ASSERT_EQ(r.size(), 1u);
  EXPECT_EQ(r[0], frame(0x581, {0x10, 's', 'e', 'r', 'v', 'o', ' ', 'd'}));
  r = exchange(0x601, {0x60, 0, 0, 0, 0, 0, 0, 0});
  ASSERT_EQ(r.size(), 1u);
  // Last segment: toggle 0, 3 unused bytes (n = 3 << 1), c = 1.
  EXPECT_EQ(r[0], frame(0x581, {0x07, 'r', 'i', 'v', 'e', 0, 0, 0}));
}

TEST_F(SdoServerTest, SegmentedUploadWithWrongToggleAborts) {
  exchange(0x601, {0x40, 0x08, 0x10, 0x00, 0, 0, 0, 0});
  const auto r = exchange(0x601, {0x70, 0, 0, 0, 0, 0, 0, 0});
  ASSERT_EQ(r.size(), 1u);
  EXPECT_EQ(r[0], frame(0x581, {0x80, 0x08, 0x10, 0x00, 0x00, 0x00, 0x03, 0x05}));
}

TEST_F(SdoServerTest, ExpeditedDownloadOfHeartbeatTimeGivesBeatsEveryFourSeconds) {
  auto r = exchange(0x601, {0x2B, 0x17, 0x10, 0x00, 0xA0, 0x0F, 0x00, 0x00});
  ASSERT_EQ(r.size(), 1u);
  EXPECT_EQ(r[0], frame(0x581, {0x60, 0x17, 0x10, 0x00, 0, 0, 0, 0}));
  r = exchange(0x601, {0x40, 0x17, 0x10, 0x00, 0, 0, 0, 0});
  ASSERT_EQ(r.size(), 1u);
  EXPECT_EQ(r[0], frame(0x581, {0x4B, 0x17, 0x10, 0x00, 0xA0, 0x0F, 0, 0}));

  received.clear();
  advance(3.999);
  EXPECT_TRUE(frames_with_id(0x701).empty());
  advance(0.001);
  ASSERT_EQ(frames_with_id(0x701).size(), 1u);
  EXPECT_EQ(frames_with_id(0x701)[0], frame(0x701, {0x7F}));  // pre-operational
  advance(8.0);
  EXPECT_EQ(frames_with_id(0x701).size(), 3u);
  // Only node 1 was configured.
  EXPECT_TRUE(frames_with_id(0x703).empty());
  EXPECT_TRUE(frames_with_id(0x704).empty());
}

TEST_F(SdoServerTest, SegmentedDownload) {
  // 0x1006 = 1000 us, segmented with size indicated (4 bytes).
  auto r = exchange(0x601, {0x21, 0x06, 0x10, 0x00, 4, 0, 0, 0});
  ASSERT_EQ(r.size(), 1u);
  EXPECT_EQ(r[0], frame(0x581, {0x60, 0x06, 0x10, 0x00, 0, 0, 0, 0}));
  r = exchange(0x601, {0x07, 0xE8, 0x03, 0x00, 0x00, 0, 0, 0});
  ASSERT_EQ(r.size(), 1u);
  EXPECT_EQ(r[0], frame(0x581, {0x20, 0, 0, 0, 0, 0, 0, 0}));
  EXPECT_EQ(bench->drive().od().get<std::uint32_t>(0x1006, 0), 1000u);
}

TEST_F(SdoServerTest, SegmentedDownloadOfWrongSizeAbortsAtInitiate) {
  const auto r = exchange(0x601, {0x21, 0x06, 0x10, 0x00, 9, 0, 0, 0});
  ASSERT_EQ(r.size(), 1u);
  EXPECT_EQ(r[0], frame(0x581, {0x80, 0x06, 0x10, 0x00, 0x10, 0x00, 0x07, 0x06}));
}

struct AbortCase {
  const char* name;
  std::array<std::uint8_t, 8> request;
  std::array<std::uint8_t, 8> response;
};

TEST_F(SdoServerTest, AbortCodes) {
  const AbortCase cases[] = {
      {"no object",
       {0x40, 0x45, 0x23, 0x00, 0, 0, 0, 0},
       {0x80, 0x45, 0x23, 0x00, 0x00, 0x00, 0x02, 0x06}},
      {"no sub-index",
       {0x40, 0x18, 0x10, 0x09, 0, 0, 0, 0},
       {0x80, 0x18, 0x10, 0x09, 0x11, 0x00, 0x09, 0x06}},
      {"read-only",
       {0x23, 0x00, 0x10, 0x00, 1, 2, 3, 4},
       {0x80, 0x00, 0x10, 0x00, 0x02, 0x00, 0x01, 0x06}},
      {"read-only statusword",
       {0x2B, 0x41, 0x60, 0x00, 1, 0, 0, 0},
       {0x80, 0x41, 0x60, 0x00, 0x02, 0x00, 0x01, 0x06}},
      {"write-only",
       {0x40, 0x00, 0x2F, 0x00, 0, 0, 0, 0},
       {0x80, 0x00, 0x2F, 0x00, 0x01, 0x00, 0x01, 0x06}},
      {"length mismatch",
       {0x2B, 0x05, 0x10, 0x00, 0x80, 0, 0, 0},
       {0x80, 0x05, 0x10, 0x00, 0x10, 0x00, 0x07, 0x06}},
      {"value range (mode 5)",
       {0x2F, 0x60, 0x60, 0x00, 5, 0, 0, 0},
       {0x80, 0x60, 0x60, 0x00, 0x30, 0x00, 0x09, 0x06}},
      {"value range (quick stop option 9)",
       {0x2B, 0x5A, 0x60, 0x00, 9, 0, 0, 0},
       {0x80, 0x5A, 0x60, 0x00, 0x30, 0x00, 0x09, 0x06}},
      {"bad command specifier 7",
       {0xE0, 0x00, 0x10, 0x00, 0, 0, 0, 0},
       {0x80, 0x00, 0x10, 0x00, 0x01, 0x00, 0x04, 0x05}},
      {"block upload not offered",
       {0xA0, 0x00, 0x10, 0x00, 0, 0, 0, 0},
       {0x80, 0x00, 0x10, 0x00, 0x01, 0x00, 0x04, 0x05}},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.name);
    received.clear();
    master->send(can::Frame::make(0x601, c.request));
    io.poll();
    io.restart();
    ASSERT_EQ(received.size(), 1u);
    EXPECT_EQ(received[0], can::Frame::make(0x581, c.response));
  }
}

TEST_F(SdoServerTest, SegmentWithoutTransferIsABadCommand) {
  const auto r = exchange(0x603, {0x60, 0, 0, 0, 0, 0, 0, 0});
  ASSERT_EQ(r.size(), 1u);
  EXPECT_EQ(r[0].id, 0x583u);
  EXPECT_EQ(r[0].data[0], 0x80);
  EXPECT_EQ(r[0].data[4], 0x01);
  EXPECT_EQ(r[0].data[7], 0x05);
}

TEST_F(SdoServerTest, ClientAbortGetsNoAnswer) {
  exchange(0x601, {0x40, 0x08, 0x10, 0x00, 0, 0, 0, 0});
  EXPECT_TRUE(exchange(0x601, {0x80, 0x08, 0x10, 0x00, 0, 0, 0, 0x08}).empty());
  // The transfer is gone: a segment request is now refused.
  const auto r = exchange(0x601, {0x60, 0, 0, 0, 0, 0, 0, 0});
  ASSERT_EQ(r.size(), 1u);
  EXPECT_EQ(r[0].data[0], 0x80);
}

TEST_F(SdoServerTest, IdentityObject) {
  const auto r = exchange(0x604, {0x40, 0x18, 0x10, 0x02, 0, 0, 0, 0});
  ASSERT_EQ(r.size(), 1u);
  EXPECT_EQ(r[0], frame(0x584, {0x43, 0x18, 0x10, 0x02, 0x04, 0x04, 0x00, 0x00}));
}

}  // namespace
}  // namespace wavebench::simdevices::testing
