#include "wavebench/procedures/dynamic_te_input.hpp"

namespace wavebench::procedures {

DynamicTeInput dynamic_te_input(std::span<const storage::SyncSample> samples) {
  DynamicTeInput in;
  bool first = true;
  std::int64_t t0 = 0, last = 0;
  for (const auto& s : samples) {
    in.missed_cycles += s.missed_before;
    if (!s.valid(storage::kThetaInValid) || !s.valid(storage::kThetaOutValid)) {
      ++in.skipped_invalid;
      continue;
    }
    if (!first && s.receive_time_ns <= last) {
      ++in.skipped_out_of_order;
      continue;
    }
    if (first) {
      t0 = s.receive_time_ns;
      first = false;
    }
    last = s.receive_time_ns;
    in.time_s.push_back(1e-9 * static_cast<double>(s.receive_time_ns - t0));
    in.theta_in_rad.push_back(s.theta_in_rad);
    in.theta_out_rad.push_back(s.theta_out_rad);
  }
  return in;
}

}  // namespace wavebench::procedures
