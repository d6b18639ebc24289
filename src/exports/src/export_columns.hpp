#pragma once
// The columns of an exported sample log, in file order: the record's integers, then every
// channel as doubles (NaN where the channel did not arrive in that cycle).

#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "wavebench/storage/channel_info.hpp"
#include "wavebench/storage/sync_sample.hpp"

namespace wavebench::exports::detail {

enum class ColumnType { kUint32, kUint64, kInt64, kDouble };

struct ExportColumn {
  std::string name;
  std::string unit;  // "" for counters and flags
  std::string description;
  ColumnType type = ColumnType::kDouble;
  std::function<std::int64_t(const storage::SyncSample&)> integer;  // the integer types
  std::function<double(const storage::SyncSample&)> real;           // kDouble
};

std::vector<ExportColumn> export_columns(std::span<const storage::ChannelInfo> extra);

}  // namespace wavebench::exports::detail
