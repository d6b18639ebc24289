#pragma once
// CSV export of a sample log: one row per SYNC cycle, invalid channels left empty.

#include <filesystem>
#include <ostream>
#include <span>

#include "wavebench/storage/channel_info.hpp"
#include "wavebench/storage/sync_sample.hpp"

namespace wavebench::storage {

// Extra channels follow the core ones as columns "<name>_<unit>" (unit in [a-z0-9_]).
void write_samples_csv(std::span<const SyncSample> samples, std::ostream& out,
                       std::span<const ChannelInfo> extra = {});
// Reads `log`, writes `csv`; returns the number of rows. Throws on I/O errors naming the path.
std::size_t export_sample_log_csv(const std::filesystem::path& log,
                                  const std::filesystem::path& csv);

}  // namespace wavebench::storage
