#pragma once
// CSV export of a sample log: one row per SYNC cycle, invalid channels left empty.

#include <filesystem>
#include <ostream>
#include <span>

#include "wavebench/storage/sync_sample.hpp"

namespace wavebench::storage {

void write_samples_csv(std::span<const SyncSample> samples, std::ostream& out);
// Reads `log`, writes `csv`; returns the number of rows. Throws on I/O errors naming the path.
std::size_t export_sample_log_csv(const std::filesystem::path& log,
                                  const std::filesystem::path& csv);

}  // namespace wavebench::storage
