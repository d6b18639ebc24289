#include "wavebench/analysis/min_max_envelope.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace wavebench::analysis {

MinMaxEnvelope::MinMaxEnvelope(double t0, double t1, std::size_t columns, std::size_t series_count)
    : t0_(t0), t1_(t1), columns_(columns), series_count_(series_count) {
  if (!std::isfinite(t0) || !std::isfinite(t1) || !(t1 >= t0) || columns == 0 ||
      series_count == 0) {
    throw std::invalid_argument(
        "min_max_envelope: expected finite t1 >= t0, at least one column and one series; got "
        "t0 " +
        std::to_string(t0) + ", t1 " + std::to_string(t1) + ", " + std::to_string(columns) +
        " columns, " + std::to_string(series_count) + " series");
  }
  width_ = (t1 - t0) / static_cast<double>(columns);
}

// The column min_max_columns puts t in: the first whose end (t0 + width · (c + 1), t1 for the
// last) lies above t. Computed from the same products so that a sample on a boundary lands
// where it lands there.
std::size_t MinMaxEnvelope::column_of(double t) const {
  const double guess = width_ > 0 ? std::floor((t - t0_) / width_) : 0.0;
  auto c = static_cast<std::size_t>(std::clamp(guess, 0.0, static_cast<double>(columns_ - 1)));
  while (c > 0 && t < t0_ + width_ * static_cast<double>(c)) --c;
  while (c + 1 < columns_ && t >= t0_ + width_ * static_cast<double>(c + 1)) ++c;
  return c;
}

void MinMaxEnvelope::bin(double t, const double* values, std::uint64_t order) {
  const std::size_t c = column_of(t);
  column_seen_[c] = true;
  for (std::size_t k = 0; k < series_count_; ++k) {
    const double v = values[k];
    if (!std::isfinite(v)) continue;
    Extreme& lo = lo_[c * series_count_ + k];
    Extreme& hi = hi_[c * series_count_ + k];
    // Strict comparisons keep the first occurrence, as min_max_columns does.
    if (!lo.set || v < lo.value) lo = {v, order, true};
    if (!hi.set || v > hi.value) hi = {v, order, true};
  }
}

void MinMaxEnvelope::add(double t, std::span<const double> values) {
  if (values.size() != series_count_) {
    throw std::invalid_argument("min_max_envelope: got " + std::to_string(values.size()) +
                                " values; expected " + std::to_string(series_count_));
  }
  if (!(t >= t0_ && t <= t1_)) {
    ++outside_;
    return;
  }
  const std::uint64_t order = in_range_++;
  if (!binned_) {
    raw_t_.push_back(t);
    raw_values_.insert(raw_values_.end(), values.begin(), values.end());
    if (raw_t_.size() <= 2 * columns_) return;
    // More than 2 × columns: from here on the columns, the samples so far binned first.
    binned_ = true;
    column_seen_.assign(columns_, false);
    lo_.assign(columns_ * series_count_, {});
    hi_.assign(columns_ * series_count_, {});
    for (std::size_t i = 0; i < raw_t_.size(); ++i) {
      bin(raw_t_[i], &raw_values_[i * series_count_], i);
    }
    raw_t_ = {};
    raw_values_ = {};
    return;
  }
  bin(t, values.data(), order);
}

DecimatedTrace MinMaxEnvelope::result() const {
  DecimatedTrace out;
  out.series.resize(series_count_);
  out.samples_in_range = in_range_;
  if (!binned_) {
    out.full_resolution = true;
    out.t = raw_t_;
    for (std::size_t k = 0; k < series_count_; ++k) {
      out.series[k].reserve(raw_t_.size());
      for (std::size_t i = 0; i < raw_t_.size(); ++i) {
        out.series[k].push_back(raw_values_[i * series_count_ + k]);
      }
    }
    return out;
  }
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (std::size_t c = 0; c < columns_; ++c) {
    if (!column_seen_[c]) continue;
    const double start = t0_ + width_ * static_cast<double>(c);
    out.t.push_back(start + 0.25 * width_);
    out.t.push_back(start + 0.75 * width_);
    for (std::size_t k = 0; k < series_count_; ++k) {
      const Extreme& lo = lo_[c * series_count_ + k];
      const Extreme& hi = hi_[c * series_count_ + k];
      auto& column = out.series[k];
      if (!lo.set) {
        column.push_back(nan);
        column.push_back(nan);
      } else {
        const bool lo_first = lo.order <= hi.order;
        column.push_back(lo_first ? lo.value : hi.value);
        column.push_back(lo_first ? hi.value : lo.value);
      }
    }
  }
  return out;
}

}  // namespace wavebench::analysis
