#include "wavebench/bench/sync_lateness_histogram.hpp"

#include <algorithm>
#include <cmath>

namespace wavebench::bench {

void SyncLatenessHistogram::add(double lateness_s) noexcept {
  const double us = std::max(0.0, lateness_s * 1e6);
  const auto bin = std::min<std::size_t>(static_cast<std::size_t>(us), kBins - 1);
  ++bins_[bin];
  ++count_;
  max_ = std::max(max_, std::max(0.0, lateness_s));
}

double SyncLatenessHistogram::percentile(double q) const noexcept {
  if (count_ == 0) return 0;
  const auto rank = static_cast<std::uint64_t>(std::ceil(std::clamp(q, 0.0, 1.0) * count_));
  std::uint64_t seen = 0;
  for (std::size_t i = 0; i < kBins; ++i) {
    seen += bins_[i];
    if (seen >= std::max<std::uint64_t>(rank, 1)) return (i + 0.5) * 1e-6;
  }
  return max_;
}

}  // namespace wavebench::bench
