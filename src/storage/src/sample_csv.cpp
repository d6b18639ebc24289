#include "wavebench/storage/sample_csv.hpp"

#include <charconv>
#include <fstream>
#include <stdexcept>

#include "wavebench/storage/sample_log.hpp"

namespace wavebench::storage {

namespace {
// Shortest text that reads back to the same double.
void field(std::ostream& out, const SyncSample& s, SampleFlag channel, double value) {
  out << ',';
  if (!s.valid(channel)) return;
  char buf[32];
  const auto result = std::to_chars(buf, buf + sizeof buf, value);
  out.write(buf, result.ptr - buf);
}
}  // namespace

void write_samples_csv(std::span<const SyncSample> samples, std::ostream& out) {
  out << "index,sync_counter,receive_time_ns,theta_in_rad,theta_out_rad,input_speed_rad_s,"
         "torque_nm,brake_current_a,brake_torque_nm,missed_before,gap,counter_anomaly\n";
  for (const auto& s : samples) {
    out << s.index << ',' << s.sync_counter << ',' << s.receive_time_ns;
    field(out, s, kThetaInValid, s.theta_in_rad);
    field(out, s, kThetaOutValid, s.theta_out_rad);
    field(out, s, kInputSpeedValid, s.input_speed_rad_s);
    field(out, s, kTorqueValid, s.torque_nm);
    field(out, s, kBrakeCurrentValid, s.brake_current_a);
    field(out, s, kBrakeTorqueValid, s.brake_torque_nm);
    out << ',' << s.missed_before << ',' << ((s.flags & kGapBefore) ? 1 : 0) << ','
        << ((s.flags & kCounterAnomaly) ? 1 : 0) << '\n';
  }
}

std::size_t export_sample_log_csv(const std::filesystem::path& log,
                                  const std::filesystem::path& csv) {
  const auto contents = read_sample_log(log);
  std::ofstream out(csv);
  if (!out) throw std::runtime_error("sample CSV: cannot create " + csv.string());
  write_samples_csv(contents.samples, out);
  out.flush();
  if (!out) throw std::runtime_error("sample CSV: write failed for " + csv.string());
  return contents.samples.size();
}

}  // namespace wavebench::storage
