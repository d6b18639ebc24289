#pragma once
// How late each SYNC left after its deadline (real clock): 1 µs bins up to 100 ms, so that a
// 10-minute run at 1 kHz keeps exact percentiles in constant memory.

#include <cstdint>
#include <vector>

namespace wavebench::bench {

class SyncLatenessHistogram {
 public:
  SyncLatenessHistogram() : bins_(kBins, 0) {}
  void add(double lateness_s) noexcept;
  // Fraction q in [0, 1]; 0 when empty.
  double percentile(double q) const noexcept;
  double max() const noexcept { return max_; }
  std::uint64_t count() const noexcept { return count_; }

 private:
  static constexpr std::size_t kBins = 100000;  // 1 µs each; the last bin collects the rest
  std::vector<std::uint32_t> bins_;
  std::uint64_t count_ = 0;
  double max_ = 0;
};

}  // namespace wavebench::bench
