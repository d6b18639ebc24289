#include "wavebench/can/error_frame.hpp"

#include <gtest/gtest.h>
#include <linux/can.h>
#include <linux/can/error.h>

namespace wavebench::can {
namespace {

Frame error_frame(std::uint32_t cls, std::uint8_t ctrl = 0) {
  Frame f;
  f.error = true;
  f.id = cls;
  f.len = 8;
  f.data[1] = ctrl;
  return f;
}

TEST(ErrorFrame, BusOffIsReported) {
  const auto ev = classify_error_frame(error_frame(CAN_ERR_BUSOFF));
  ASSERT_EQ(ev.size(), 1U);
  EXPECT_EQ(ev[0].kind, BusEventKind::bus_off);
}

TEST(ErrorFrame, ControllerPassiveAndWarning) {
  const auto passive = classify_error_frame(error_frame(CAN_ERR_CRTL, CAN_ERR_CRTL_TX_PASSIVE));
  ASSERT_EQ(passive.size(), 1U);
  EXPECT_EQ(passive[0].kind, BusEventKind::error_passive);
  const auto warning = classify_error_frame(error_frame(CAN_ERR_CRTL, CAN_ERR_CRTL_RX_WARNING));
  ASSERT_EQ(warning.size(), 1U);
  EXPECT_EQ(warning[0].kind, BusEventKind::error_warning);
}

TEST(ErrorFrame, RestartedAndProtocolAndCombined) {
  const auto ev =
      classify_error_frame(error_frame(CAN_ERR_RESTARTED | CAN_ERR_ACK | CAN_ERR_BUSOFF));
  ASSERT_EQ(ev.size(), 3U);
  EXPECT_EQ(ev[0].kind, BusEventKind::bus_off);
  EXPECT_EQ(ev[1].kind, BusEventKind::restarted);
  EXPECT_EQ(ev[2].kind, BusEventKind::protocol);
}

TEST(ErrorFrame, DataFramesAreNotErrors) {
  EXPECT_TRUE(classify_error_frame(Frame::make(0x040, {0, 0x20})).empty());
}

TEST(ErrorFrame, ErrorFlagMatchesLinux) {
  EXPECT_EQ(kErrorFlag, CAN_ERR_FLAG);
  EXPECT_EQ(error_frame(CAN_ERR_BUSOFF).raw_id(), CAN_ERR_FLAG | CAN_ERR_BUSOFF);
}

}  // namespace
}  // namespace wavebench::can
