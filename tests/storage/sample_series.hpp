#pragma once
// A deterministic series of complete samples for the sample-log tests: sample i has its own
// counter, time and angles, so a record read back can be told from its neighbours.

#include <cstdint>

#include "wavebench/storage/sync_sample.hpp"

namespace wavebench::storage::testing {

inline SyncSample make_sample(std::uint64_t i) {
  SyncSample s;
  s.sync_counter = static_cast<std::uint32_t>(i % 240 + 1);
  s.flags = kAllChannelsValid;
  s.receive_time_ns = 1'000'000'000 + static_cast<std::int64_t>(i) * 1'000'000;
  s.theta_in_rad = 0.01 * static_cast<double>(i);
  s.theta_out_rad = -0.0001 * static_cast<double>(i);
  s.input_speed_rad_s = 10.47;
  s.torque_nm = 60.0 + static_cast<double>(i);
  s.brake_current_a = 0.5;
  s.brake_torque_nm = 59.5;
  return s;
}

}  // namespace wavebench::storage::testing
