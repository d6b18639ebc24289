#pragma once
// The dynamic-TE record taken from acquired SYNC samples: only samples with both angles valid,
// on their own receive timestamps. Missing cycles stay missing (the spectra resample on the
// real time and angle axes), they are only counted.

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "wavebench/storage/sync_sample.hpp"

namespace wavebench::procedures {

struct DynamicTeInput {
  std::vector<double> time_s;  // receive time, from the first kept sample
  std::vector<double> theta_in_rad;
  std::vector<double> theta_out_rad;
  std::size_t skipped_invalid = 0;        // an angle missing in the cycle
  std::size_t skipped_out_of_order = 0;   // timestamp not after the previous kept sample
  std::size_t skipped_not_advancing = 0;  // output angle not past the previous kept one
  std::size_t missed_cycles = 0;          // sum of missed_before over the samples
  // receive_time_ns of the first and last kept sample: where the record is in samples.wbs.
  std::int64_t first_receive_time_ns = 0, last_receive_time_ns = 0;
};

DynamicTeInput dynamic_te_input(std::span<const storage::SyncSample> samples);

}  // namespace wavebench::procedures
