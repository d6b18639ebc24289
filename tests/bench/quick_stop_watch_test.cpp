// The quick stop's frame and RPDO mapping byte for byte, which statuswords confirm it, and the
// watch's verdicts in bench time (quick_stop_watch.hpp).
#include "wavebench/bench/quick_stop_watch.hpp"

#include <gtest/gtest.h>

namespace wavebench::bench {
namespace {

TEST(QuickStop, FrameIsControlwordQuickStopInRpdoOne) {
  const auto f = quick_stop_frame(5);
  EXPECT_EQ(f.id, 0x205U);
  EXPECT_FALSE(f.extended);
  ASSERT_EQ(f.len, 2);
  EXPECT_EQ(f.data[0], 0x02);
  EXPECT_EQ(f.data[1], 0x00);

  const auto rpdo = quick_stop_rpdo(5);
  EXPECT_EQ(rpdo.cob_id, 0x205U);
  EXPECT_EQ(rpdo.transmission_type, 255);  // event-driven: taken on reception
  ASSERT_EQ(rpdo.entries.size(), 1U);
  EXPECT_EQ(rpdo.entries[0].encode(), 0x60400010U);
}

TEST(QuickStop, TakenWhenQuickStopActiveOrPowerStageOff) {
  EXPECT_TRUE(quick_stop_taken(0x0217));   // quick stop active
  EXPECT_TRUE(quick_stop_taken(0x0007));   // quick stop active
  EXPECT_TRUE(quick_stop_taken(0x0250));   // switch on disabled
  EXPECT_TRUE(quick_stop_taken(0x0231));   // ready to switch on
  EXPECT_TRUE(quick_stop_taken(0x0000));   // not ready to switch on
  EXPECT_TRUE(quick_stop_taken(0x0218));   // fault
  EXPECT_TRUE(quick_stop_taken(0x020F));   // fault reaction active
  EXPECT_FALSE(quick_stop_taken(0x1637));  // operation enabled
  EXPECT_FALSE(quick_stop_taken(0x0233));  // switched on
}

TEST(QuickStopWatch, ConfirmedByTheFirstStatuswordThatShowsIt) {
  QuickStopWatch w;
  EXPECT_EQ(w.on_cycle(0, 0x0237), QuickStopWatch::Verdict::kIdle);
  w.start(1.0, 0.05);
  EXPECT_TRUE(w.pending());
  EXPECT_EQ(w.on_cycle(1.001, 0x0237), QuickStopWatch::Verdict::kWaiting);
  EXPECT_EQ(w.on_cycle(1.002, std::nullopt), QuickStopWatch::Verdict::kWaiting);
  EXPECT_EQ(w.last_statusword(), 0x0237);
  EXPECT_EQ(w.on_cycle(1.003, 0x0217), QuickStopWatch::Verdict::kConfirmed);
  EXPECT_FALSE(w.pending());
  EXPECT_EQ(w.on_cycle(2.0, 0x0237), QuickStopWatch::Verdict::kIdle);
}

TEST(QuickStopWatch, TimesOutWhenTheStatuswordNeverShowsIt) {
  QuickStopWatch w;
  w.start(1.0, 0.05);
  EXPECT_EQ(w.on_cycle(1.049, 0x0237), QuickStopWatch::Verdict::kWaiting);
  EXPECT_EQ(w.on_cycle(1.050, 0x0237), QuickStopWatch::Verdict::kTimedOut);
  EXPECT_FALSE(w.pending());
  EXPECT_EQ(w.last_statusword(), 0x0237);

  // A drive that sends nothing times out too, with no statusword to report.
  w.start(3.0, 0.05);
  EXPECT_FALSE(w.last_statusword());
  EXPECT_EQ(w.on_cycle(3.02, std::nullopt), QuickStopWatch::Verdict::kWaiting);
  EXPECT_EQ(w.on_cycle(3.06, std::nullopt), QuickStopWatch::Verdict::kTimedOut);
  EXPECT_FALSE(w.last_statusword());
  w.start(4.0, 0.05);
  w.reset();
  EXPECT_FALSE(w.pending());
}

}  // namespace
}  // namespace wavebench::bench
