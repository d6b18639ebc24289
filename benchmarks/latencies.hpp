#pragma once
// Request latencies of a benchmark and their quantiles (nearest rank), shared by the
// history and fleet benchmarks.

#include <algorithm>
#include <cstddef>
#include <vector>

namespace wavebench::benchmarks {

struct Latencies {
  std::vector<double> ms;
  double quantile(double q) {
    std::sort(ms.begin(), ms.end());
    return ms.empty() ? 0
                      : ms[std::min(ms.size() - 1,
                                    static_cast<std::size_t>(q * static_cast<double>(ms.size())))];
  }
};

}  // namespace wavebench::benchmarks
