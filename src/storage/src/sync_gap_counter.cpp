#include "wavebench/storage/sync_gap_counter.hpp"

#include <stdexcept>
#include <string>

namespace wavebench::storage {

SyncGapCounter::SyncGapCounter(SyncCounterRange range) : range_(range) {
  if (range.last < range.first) {
    throw std::invalid_argument("sync counter range: last = " + std::to_string(range.last) +
                                " is below first = " + std::to_string(range.first) +
                                "; expected first <= last");
  }
}

void SyncGapCounter::observe(SyncSample& sample) {
  ++totals_.samples;
  sample.missed_before = 0;
  if (!sample.complete()) ++totals_.incomplete_samples;
  const std::uint32_t c = sample.sync_counter;
  if (c < range_.first || c > range_.last) {
    sample.flags |= kCounterAnomaly;
    ++totals_.anomalies;
    return;  // keep the previous counter: the next good one still measures the gap
  }
  if (previous_) {
    const std::uint64_t period = range_.period();
    const std::uint64_t step = (period + c - *previous_) % period;
    if (step == 0) {
      // A repeated counter is a duplicate frame or exactly one period lost; neither is a gap
      // that can be sized, so it is flagged as an anomaly.
      sample.flags |= kCounterAnomaly;
      ++totals_.anomalies;
    } else if (step > 1) {
      sample.missed_before = static_cast<std::uint32_t>(step - 1);
      sample.flags |= kGapBefore;
      ++totals_.gaps;
      totals_.missed_cycles += step - 1;
    }
  }
  previous_ = c;
}

}  // namespace wavebench::storage
