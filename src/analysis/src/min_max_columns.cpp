#include "wavebench/analysis/min_max_columns.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace wavebench::analysis {

DecimatedTrace min_max_columns(std::span<const double> t,
                               std::span<const std::span<const double>> series, double t0,
                               double t1, std::size_t columns) {
  for (const auto& s : series) {
    if (s.size() != t.size()) {
      throw std::invalid_argument("min_max_columns: a series has " + std::to_string(s.size()) +
                                  " values for " + std::to_string(t.size()) + " times");
    }
  }
  if (!(t1 >= t0) || columns == 0) {
    throw std::invalid_argument("min_max_columns: expected t1 >= t0 and at least one column");
  }
  const auto first = static_cast<std::size_t>(std::lower_bound(t.begin(), t.end(), t0) - t.begin());
  const auto last = static_cast<std::size_t>(std::upper_bound(t.begin(), t.end(), t1) - t.begin());
  DecimatedTrace out;
  out.series.resize(series.size());
  out.samples_in_range = last > first ? last - first : 0;
  if (out.samples_in_range <= 2 * columns) {
    out.full_resolution = true;
    out.t.assign(t.begin() + static_cast<std::ptrdiff_t>(first),
                 t.begin() + static_cast<std::ptrdiff_t>(std::max(first, last)));
    for (std::size_t k = 0; k < series.size(); ++k) {
      out.series[k].assign(series[k].begin() + static_cast<std::ptrdiff_t>(first),
                           series[k].begin() + static_cast<std::ptrdiff_t>(std::max(first, last)));
    }
    return out;
  }
  const double width = (t1 - t0) / static_cast<double>(columns);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::size_t i = first;
  for (std::size_t c = 0; c < columns && i < last; ++c) {
    const double end = c + 1 == columns ? t1 : t0 + width * static_cast<double>(c + 1);
    std::size_t j = i;
    while (j < last && (t[j] < end || (c + 1 == columns && t[j] <= end))) ++j;
    if (j == i) continue;  // no sample in this column
    const double column_start = t0 + width * static_cast<double>(c);
    out.t.push_back(column_start + 0.25 * width);
    out.t.push_back(column_start + 0.75 * width);
    for (std::size_t k = 0; k < series.size(); ++k) {
      std::size_t lo = j, hi = j;
      for (std::size_t n = i; n < j; ++n) {
        const double v = series[k][n];
        if (!std::isfinite(v)) continue;
        if (lo == j || v < series[k][lo]) lo = n;
        if (hi == j || v > series[k][hi]) hi = n;
      }
      auto& column = out.series[k];
      if (lo == j) {
        column.push_back(nan);
        column.push_back(nan);
      } else {
        column.push_back(series[k][std::min(lo, hi)]);
        column.push_back(series[k][std::max(lo, hi)]);
      }
    }
    i = j;
  }
  return out;
}

}  // namespace wavebench::analysis
