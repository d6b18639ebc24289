#include "export_columns.hpp"

#include <limits>

namespace wavebench::exports::detail {

namespace {

using storage::SyncSample;

ExportColumn integer(std::string name, std::string description, ColumnType type,
                     std::function<std::int64_t(const SyncSample&)> get) {
  ExportColumn c;
  c.name = std::move(name);
  c.description = std::move(description);
  c.type = type;
  c.integer = std::move(get);
  return c;
}

// A channel of the sample by its position (core ones, then extra ones), NaN where it did not
// arrive.
ExportColumn channel(const std::string& name, const std::string& unit, std::size_t position) {
  ExportColumn c;
  c.name = name;
  c.unit = unit;
  c.description = "channel " + name + " [" + unit + "], NaN where it did not arrive";
  c.real = [position](const SyncSample& s) {
    return s.arrived(position) ? s.value(position) : std::numeric_limits<double>::quiet_NaN();
  };
  return c;
}

}  // namespace

std::vector<ExportColumn> export_columns(std::span<const storage::ChannelInfo> extra) {
  std::vector<ExportColumn> c;
  c.push_back(integer("index", "position in the sample log", ColumnType::kUint64,
                      [](const SyncSample& s) { return static_cast<std::int64_t>(s.index); }));
  c.push_back(integer("sync_counter", "SYNC counter as received (CiA 301 0x1019)",
                      ColumnType::kUint32, [](const SyncSample& s) { return s.sync_counter; }));
  c.push_back(integer("flags", "SampleFlag bits (docs/sample-log.md)", ColumnType::kUint32,
                      [](const SyncSample& s) { return s.flags; }));
  c.push_back(integer("receive_time_ns", "receive timestamp [ns]", ColumnType::kInt64,
                      [](const SyncSample& s) { return s.receive_time_ns; }));
  c.push_back(integer("missed_before", "SYNC cycles missed just before the sample",
                      ColumnType::kUint32, [](const SyncSample& s) { return s.missed_before; }));
  for (std::size_t i = 0; i < storage::kCoreChannels.size(); ++i) {
    const auto& core = storage::kCoreChannels[i];
    c.push_back(channel(std::string(core.name), std::string(core.unit), i));
  }
  if (!extra.empty()) {
    c.push_back(integer("extra_valid", "bit i: extra channel i arrived", ColumnType::kUint32,
                        [](const SyncSample& s) { return s.extra_valid; }));
  }
  for (std::size_t i = 0; i < extra.size() && i < storage::kMaxExtraChannels; ++i) {
    c.push_back(channel(extra[i].name, extra[i].unit, storage::kCoreChannelCount + i));
  }
  return c;
}

}  // namespace wavebench::exports::detail
