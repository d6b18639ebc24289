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

ExportColumn channel(const storage::ChannelInfo& info, std::function<bool(const SyncSample&)> valid,
                     std::function<double(const SyncSample&)> value) {
  ExportColumn c;
  c.name = info.name;
  c.unit = info.unit;
  c.description = "channel " + info.name + " [" + info.unit + "], NaN where it did not arrive";
  c.real = [valid = std::move(valid), value = std::move(value)](const SyncSample& s) {
    return valid(s) ? value(s) : std::numeric_limits<double>::quiet_NaN();
  };
  return c;
}

}  // namespace

std::vector<ExportColumn> export_columns(std::span<const storage::ChannelInfo> extra) {
  using storage::SampleFlag;
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
  const auto core = storage::core_channels();
  const auto flag = [](SampleFlag f) { return [f](const SyncSample& s) { return s.valid(f); }; };
  c.push_back(channel(core[0], flag(storage::kThetaInValid),
                      [](const SyncSample& s) { return s.theta_in_rad; }));
  c.push_back(channel(core[1], flag(storage::kThetaOutValid),
                      [](const SyncSample& s) { return s.theta_out_rad; }));
  c.push_back(channel(core[2], flag(storage::kInputSpeedValid),
                      [](const SyncSample& s) { return s.input_speed_rad_s; }));
  c.push_back(channel(core[3], flag(storage::kTorqueValid),
                      [](const SyncSample& s) { return s.torque_nm; }));
  c.push_back(channel(core[4], flag(storage::kBrakeCurrentValid),
                      [](const SyncSample& s) { return s.brake_current_a; }));
  c.push_back(channel(core[5], flag(storage::kBrakeTorqueValid),
                      [](const SyncSample& s) { return s.brake_torque_nm; }));
  if (!extra.empty()) {
    c.push_back(integer("extra_valid", "bit i: extra channel i arrived", ColumnType::kUint32,
                        [](const SyncSample& s) { return s.extra_valid; }));
  }
  for (std::size_t i = 0; i < extra.size() && i < storage::kMaxExtraChannels; ++i) {
    c.push_back(channel(
        extra[i], [i](const SyncSample& s) { return s.extra_arrived(i); },
        [i](const SyncSample& s) { return s.extra[i]; }));
  }
  return c;
}

}  // namespace wavebench::exports::detail
