#pragma once
// min_max_columns for a record read in pieces (a sample log page by page, a CSV line by line):
// samples go in one at a time and only one extreme pair per column and series is kept, so the
// memory is that of the columns whatever the record's length. The time range is fixed up front
// (a record's first and last time are known before it is read through).
//
// On samples given in ascending time the result equals min_max_columns on the whole record with
// the same range and columns, row for row: two rows per non-empty column (min and max in the
// order they occurred), or the samples themselves while there are no more than 2 × columns.
// Samples out of time order still land in their column; the rows then follow the columns.
//
//   analysis::MinMaxEnvelope te(t_first, t_last, 1000, 2);
//   for (each sample) te.add(t, std::array{measured, predicted});
//   const analysis::DecimatedTrace rows = te.result();

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "wavebench/analysis/min_max_columns.hpp"

namespace wavebench::analysis {

class MinMaxEnvelope {
 public:
  // Throws std::invalid_argument when t1 < t0 (or either is not finite), columns or
  // series_count is zero.
  MinMaxEnvelope(double t0, double t1, std::size_t columns, std::size_t series_count);

  // `values`: one per series (NaN for a missing value). Throws std::invalid_argument on a
  // different count. A sample with t outside [t0, t1] is counted and left out.
  void add(double t, std::span<const double> values);
  void add(double t, double value) { add(t, std::span<const double>(&value, 1)); }

  DecimatedTrace result() const;
  std::size_t samples_in_range() const { return in_range_; }
  std::size_t samples_outside_range() const { return outside_; }

 private:
  struct Extreme {
    double value = 0;
    std::uint64_t order = 0;  // the sample's position among those in range
    bool set = false;
  };
  std::size_t column_of(double t) const;
  void bin(double t, const double* values, std::uint64_t order);

  double t0_, t1_, width_;
  std::size_t columns_, series_count_;
  std::size_t in_range_ = 0, outside_ = 0;
  // Until more than 2 × columns samples came: the samples themselves, row-major.
  std::vector<double> raw_t_, raw_values_;
  bool binned_ = false;
  std::vector<bool> column_seen_;
  std::vector<Extreme> lo_, hi_;  // [column * series_count + series]
};

}  // namespace wavebench::analysis
