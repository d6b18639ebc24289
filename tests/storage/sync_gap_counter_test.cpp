#include "wavebench/storage/sync_gap_counter.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

namespace wavebench::storage {
namespace {

SyncSample with_counter(std::uint32_t c) {
  SyncSample s;
  s.sync_counter = c;
  s.flags = kAllChannelsValid;
  return s;
}

TEST(SyncGapCounter, ContiguousCountersAcrossTheWrapHaveNoGap) {
  SyncGapCounter counter;  // 1..240
  for (std::uint32_t c : {238u, 239u, 240u, 1u, 2u}) {
    auto s = with_counter(c);
    counter.observe(s);
    EXPECT_EQ(s.missed_before, 0u) << c;
    EXPECT_EQ(s.flags & kGapBefore, 0u);
  }
  EXPECT_EQ(counter.totals().gaps, 0u);
  EXPECT_EQ(counter.totals().samples, 5u);
}

TEST(SyncGapCounter, GapAcrossTheWrapIsSizedAndFlaggedOnTheNextSample) {
  SyncGapCounter counter;
  auto a = with_counter(239);
  counter.observe(a);
  auto b = with_counter(3);  // 240, 1, 2 missed
  counter.observe(b);
  EXPECT_EQ(b.missed_before, 3u);
  EXPECT_NE(b.flags & kGapBefore, 0u);
  EXPECT_EQ(counter.totals().gaps, 1u);
  EXPECT_EQ(counter.totals().missed_cycles, 3u);
}

TEST(SyncGapCounter, ConfigurableEightBitRange) {
  SyncGapCounter counter(SyncCounterRange{0, 255});
  auto a = with_counter(254);
  counter.observe(a);
  auto b = with_counter(1);  // 255, 0 missed
  counter.observe(b);
  EXPECT_EQ(b.missed_before, 2u);
}

TEST(SyncGapCounter, RepeatAndOutOfRangeAreAnomaliesNotGaps) {
  SyncGapCounter counter;
  auto a = with_counter(10);
  counter.observe(a);
  auto dup = with_counter(10);
  counter.observe(dup);
  auto bad = with_counter(0);
  counter.observe(bad);
  auto next = with_counter(11);
  counter.observe(next);
  EXPECT_NE(dup.flags & kCounterAnomaly, 0u);
  EXPECT_NE(bad.flags & kCounterAnomaly, 0u);
  EXPECT_EQ(next.missed_before, 0u);
  EXPECT_EQ(counter.totals().anomalies, 2u);
  EXPECT_EQ(counter.totals().gaps, 0u);
}

TEST(SyncGapCounter, IncompleteSamplesAreCounted) {
  SyncGapCounter counter;
  auto s = with_counter(1);
  s.flags &= ~kTorqueValid;
  counter.observe(s);
  EXPECT_EQ(counter.totals().incomplete_samples, 1u);
  EXPECT_FALSE(s.complete());
}

TEST(SyncGapCounter, RejectsAnInvertedRange) {
  EXPECT_THROW(SyncGapCounter(SyncCounterRange{10, 5}), std::invalid_argument);
}

}  // namespace
}  // namespace wavebench::storage
