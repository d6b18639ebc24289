#include "wavebench/metrology/dynamic_te_input.hpp"

namespace wavebench::metrology {

bool DynamicTeSampleFilter::keep(const storage::SyncSample& s) noexcept {
  counts_.missed_cycles += s.missed_before;
  if (!s.valid(storage::kThetaInValid) || !s.valid(storage::kThetaOutValid)) {
    ++counts_.skipped_invalid;
    return false;
  }
  if (!first_ && s.receive_time_ns <= counts_.last_receive_time_ns) {
    ++counts_.skipped_out_of_order;
    return false;
  }
  if (!first_ && !((s.theta_out_rad - last_kept_out_) * direction_ > 0)) {
    ++counts_.skipped_not_advancing;
    return false;
  }
  last_kept_out_ = s.theta_out_rad;
  if (first_) {
    counts_.first_receive_time_ns = s.receive_time_ns;
    first_ = false;
  }
  counts_.last_receive_time_ns = s.receive_time_ns;
  return true;
}

DynamicTeInput dynamic_te_input(std::span<const storage::SyncSample> samples) {
  double first_out = 0, last_out = 0;
  bool any = false;
  for (const auto& s : samples) {
    if (!s.valid(storage::kThetaInValid) || !s.valid(storage::kThetaOutValid)) continue;
    if (!any) first_out = s.theta_out_rad;
    last_out = s.theta_out_rad;
    any = true;
  }
  DynamicTeSampleFilter filter(last_out < first_out ? -1.0 : 1.0);
  DynamicTeInput in;
  for (const auto& s : samples) {
    if (!filter.keep(s)) continue;
    in.time_s.push_back(filter.time_s(s));
    in.theta_in_rad.push_back(s.theta_in_rad);
    in.theta_out_rad.push_back(s.theta_out_rad);
  }
  static_cast<DynamicTeSampleCounts&>(in) = filter.counts();
  return in;
}

}  // namespace wavebench::metrology
