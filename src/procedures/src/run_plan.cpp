#include "wavebench/procedures/run_plan.hpp"

#include <algorithm>
#include <cmath>

#include "wavebench/storage/sample_log.hpp"

namespace wavebench::procedures {

namespace {
// The simulated drive's profile acceleration (50 rev/s²); real drives are of the same order,
// and the estimate only has to be right within a factor of two.
constexpr double kNominalAccelerationRad_s2 = 314;
// Target reached is seen a couple of SYNCs after the profile ends.
constexpr double kMoveHandshakeS = 0.005;
}  // namespace

double planned_move_s(double distance_rad, double speed_rad_s) {
  const double d = std::abs(distance_rad);
  if (d == 0 || !(speed_rad_s > 0)) return kMoveHandshakeS;
  const double a = kNominalAccelerationRad_s2;
  const double ramps = speed_rad_s * speed_rad_s / a;  // distance to speed up and to stop
  const double t = d >= ramps ? d / speed_rad_s + speed_rad_s / a : 2 * std::sqrt(d / a);
  return t + kMoveHandshakeS;
}

double planned_ramp_s(double speed_rad_s) {
  return std::abs(speed_rad_s) / kNominalAccelerationRad_s2 + kMoveHandshakeS;
}

RunEstimate estimate_run(const RunPlan& plan, const bench::BenchDescription& bench,
                         std::size_t extra_channels, bool twin) {
  RunEstimate e;
  e.bench_time_s = plan.bench_time_s;
  const double period = bench.sync_period_s > 0 ? bench.sync_period_s : 1e-3;
  // Clamped: an absurd request must still give a number to refuse, not an overflow.
  e.samples = static_cast<std::uint64_t>(std::ceil(std::min(plan.bench_time_s / period, 1e15)));
  e.sample_log_bytes = storage::sample_log_header_size(extra_channels) +
                       e.samples * storage::sample_log_record_size(extra_channels);
  e.twin_bytes = twin ? e.samples * kTwinCsvBytesPerSample : 0;
  e.other_bytes = kRunMarginBytes;
  return e;
}

}  // namespace wavebench::procedures
