#include "wavebench/procedures/dynamic_te_input.hpp"

namespace wavebench::procedures {

DynamicTeInput dynamic_te_input(std::span<const storage::SyncSample> samples) {
  DynamicTeInput in;
  // The way the output turns over the record, from its first and last angles: a sample whose
  // output angle does not advance that way (an encoder value repeated by a late or stale PDO)
  // is skipped and counted, instead of stopping the order analysis of a whole run.
  double first_out = 0, last_out = 0;
  bool any = false;
  for (const auto& s : samples) {
    if (!s.valid(storage::kThetaInValid) || !s.valid(storage::kThetaOutValid)) continue;
    if (!any) first_out = s.theta_out_rad;
    last_out = s.theta_out_rad;
    any = true;
  }
  const double direction = last_out < first_out ? -1.0 : 1.0;
  bool first = true;
  std::int64_t t0 = 0, last = 0;
  double last_kept_out = 0;
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
    if (!first && !((s.theta_out_rad - last_kept_out) * direction > 0)) {
      ++in.skipped_not_advancing;
      continue;
    }
    last_kept_out = s.theta_out_rad;
    if (first) {
      t0 = s.receive_time_ns;
      first = false;
    }
    last = s.receive_time_ns;
    if (in.time_s.empty()) in.first_receive_time_ns = t0;
    in.last_receive_time_ns = last;
    in.time_s.push_back(1e-9 * static_cast<double>(s.receive_time_ns - t0));
    in.theta_in_rad.push_back(s.theta_in_rad);
    in.theta_out_rad.push_back(s.theta_out_rad);
  }
  return in;
}

}  // namespace wavebench::procedures
