#pragma once
// Counts SYNC cycles missed between received samples from the SYNC counter. A gap is counted
// and flagged on the sample after it, never filled.

#include <cstdint>
#include <optional>

#include "wavebench/storage/sync_sample.hpp"

namespace wavebench::storage {

struct SyncCounterRange {
  // CiA 301: with 0x1019 (overflow) = 240 the counter runs 1, 2, ..., 240, 1, ...
  std::uint32_t first = 1;
  std::uint32_t last = 240;
  std::uint32_t period() const { return last - first + 1; }
};

struct SyncGapTotals {
  std::uint64_t samples = 0;
  std::uint64_t gaps = 0;                // samples preceded by at least one missed cycle
  std::uint64_t missed_cycles = 0;       // cycles missed in all
  std::uint64_t anomalies = 0;           // repeated or out-of-range counters
  std::uint64_t incomplete_samples = 0;  // a channel missing in the cycle
};

class SyncGapCounter {
 public:
  // Throws std::invalid_argument naming the range when last < first.
  explicit SyncGapCounter(SyncCounterRange range = {});

  // Sets missed_before and the kGapBefore / kCounterAnomaly flags on `sample`.
  void observe(SyncSample& sample);
  const SyncGapTotals& totals() const { return totals_; }
  const SyncCounterRange& range() const { return range_; }

 private:
  SyncCounterRange range_;
  std::optional<std::uint32_t> previous_;
  SyncGapTotals totals_;
};

}  // namespace wavebench::storage
