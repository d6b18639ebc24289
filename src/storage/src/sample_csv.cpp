#include "wavebench/storage/sample_csv.hpp"

#include <algorithm>
#include <charconv>
#include <fstream>
#include <stdexcept>
#include <string>

#include "wavebench/storage/sample_log.hpp"

namespace wavebench::storage {

namespace {
// Shortest text that reads back to the same double.
void field(std::ostream& out, bool valid, double value) {
  out << ',';
  if (!valid) return;
  char buf[32];
  const auto result = std::to_chars(buf, buf + sizeof buf, value);
  out.write(buf, result.ptr - buf);
}
std::string unit_slug(const std::string& unit) {
  std::string slug;
  for (const char c : unit) {
    const char lower = (c >= 'A' && c <= 'Z') ? static_cast<char>(c - 'A' + 'a') : c;
    const bool keep = (lower >= 'a' && lower <= 'z') || (lower >= '0' && lower <= '9');
    if (keep)
      slug += lower;
    else if (!slug.empty() && slug.back() != '_')
      slug += '_';
  }
  return slug;
}
}  // namespace

void write_samples_csv(std::span<const SyncSample> samples, std::ostream& out,
                       std::span<const ChannelInfo> extra) {
  out << "index,sync_counter,receive_time_ns";
  for (const auto& c : kCoreChannels) out << ',' << c.column;
  const std::size_t extras = std::min(extra.size(), kMaxExtraChannels);
  for (std::size_t i = 0; i < extras; ++i)
    out << ',' << extra[i].name << '_' << unit_slug(extra[i].unit);
  out << ",missed_before,gap,counter_anomaly\n";
  for (const auto& s : samples) {
    out << s.index << ',' << s.sync_counter << ',' << s.receive_time_ns;
    for (const auto& c : kCoreChannels) field(out, s.valid(c.valid), s.*c.value);
    for (std::size_t i = 0; i < extras; ++i) field(out, s.extra_arrived(i), s.extra[i]);
    out << ',' << s.missed_before << ',' << ((s.flags & kGapBefore) ? 1 : 0) << ','
        << ((s.flags & kCounterAnomaly) ? 1 : 0) << '\n';
  }
}

std::size_t export_sample_log_csv(const std::filesystem::path& log,
                                  const std::filesystem::path& csv) {
  const auto contents = read_sample_log(log);
  std::ofstream out(csv);
  if (!out) throw std::runtime_error("sample CSV: cannot create " + csv.string());
  write_samples_csv(contents.samples, out, contents.header.extra_channels);
  out.flush();
  if (!out) throw std::runtime_error("sample CSV: write failed for " + csv.string());
  return contents.samples.size();
}

}  // namespace wavebench::storage
