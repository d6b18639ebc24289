#pragma once
// The dynamic-TE record taken from acquired SYNC samples: only samples with both angles valid,
// on their own receive timestamps. Missing cycles stay missing (the spectra resample on the
// real time and angle axes), they are only counted.

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "wavebench/storage/sync_sample.hpp"

namespace wavebench::metrology {

struct DynamicTeSampleCounts {
  std::size_t skipped_invalid = 0;        // an angle missing in the cycle
  std::size_t skipped_out_of_order = 0;   // timestamp not after the previous kept sample
  std::size_t skipped_not_advancing = 0;  // output angle not past the previous kept one
  std::size_t missed_cycles = 0;          // sum of missed_before over the samples
  // receive_time_ns of the first and last kept sample: where the record is in samples.wbs.
  std::int64_t first_receive_time_ns = 0, last_receive_time_ns = 0;
};

// The selection one sample at a time, for a record reduced as it is acquired: a sample whose
// output angle does not advance the way the output turns (an encoder value repeated by a late
// or stale PDO) is skipped and counted, instead of stopping the order analysis of a whole run.
class DynamicTeSampleFilter {
 public:
  // `output_direction`: the sign in which the raw θ_out advances over the record (±1).
  explicit DynamicTeSampleFilter(double output_direction) : direction_(output_direction) {}
  // Whether the sample belongs to the record; counts it either way.
  bool keep(const storage::SyncSample& s) noexcept;
  const DynamicTeSampleCounts& counts() const { return counts_; }
  // Receive time of the sample kept last, from the first kept one [s].
  double time_s(const storage::SyncSample& s) const {
    return 1e-9 * static_cast<double>(s.receive_time_ns - counts_.first_receive_time_ns);
  }

 private:
  double direction_;
  DynamicTeSampleCounts counts_;
  bool first_ = true;
  double last_kept_out_ = 0;
};

struct DynamicTeInput : DynamicTeSampleCounts {
  std::vector<double> time_s;  // receive time, from the first kept sample
  std::vector<double> theta_in_rad;
  std::vector<double> theta_out_rad;
};

// The way the output turns over the record is taken from its first and last valid angles.
DynamicTeInput dynamic_te_input(std::span<const storage::SyncSample> samples);

}  // namespace wavebench::metrology
