#pragma once
// Decimation for plots: a time range split into equal columns (one per pixel column), and in
// each column the smallest and the largest value of every series, in the order they occurred.
// Unlike keeping every n-th sample this never hides a spike: the drawn envelope is the true
// one at any zoom. Columns with no finite value of a series give NaN there (a gap in the plot).
//
// Output rows: two per non-empty column, at the column's first and second half, so a line
// through them draws min and max of each series in time order. When the range holds no more
// samples than 2 × columns, the samples themselves are returned (full resolution).

#include <cstddef>
#include <span>
#include <vector>

namespace wavebench::analysis {

struct DecimatedTrace {
  std::vector<double> t;                    // row times
  std::vector<std::vector<double>> series;  // one per input series, same length as t
  bool full_resolution = false;             // the rows are the samples themselves
  std::size_t samples_in_range = 0;
};

// `t` ascending (the samples' times); each series as long as `t`. Samples with t outside
// [t0, t1] are ignored. columns ≥ 1. Throws std::invalid_argument on mismatched lengths,
// t1 < t0 or zero columns.
DecimatedTrace min_max_columns(std::span<const double> t,
                               std::span<const std::span<const double>> series, double t0,
                               double t1, std::size_t columns);

}  // namespace wavebench::analysis
