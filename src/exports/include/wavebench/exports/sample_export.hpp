#pragma once
// A run's samples and results in one file for MATLAB (.mat, libmatio), Python (HDF5, libhdf5)
// or any tool (CSV, JSON), written from pages of the sample log: the log on disk
// (storage::read_sample_log_page) or the daemon's samples API. Never the whole log at once:
// CSV, JSON and HDF5 take one page at a time; the .mat file collects columns (a MAT 5 variable
// is written whole), as many per pass over the pages as fit 64 MiB.
//
// What the .mat and HDF5 files hold (docs/formats/exports.md):
//   index, sync_counter, flags, receive_time_ns, missed_before, extra_valid   (integers)
//   theta_in, theta_out, input_speed, torque, brake_current, brake_torque, the extra channels
//                                      (doubles, SI; NaN where the channel did not arrive)
//   units            (.mat: struct channel -> unit; HDF5: a "unit" attribute on each dataset)
//   results_json     the run's results.json as text; run_json the run's record as text
//   results          the results' numbers (objects as structs / groups, numeric lists as
//                    vectors)
// HDF5 puts the columns under /samples and the rest at the root.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <span>
#include <string>

#include "wavebench/exports/export_format.hpp"
#include "wavebench/storage/channel_info.hpp"
#include "wavebench/storage/sample_log.hpp"

namespace wavebench::exports {

// Records [from, from + count) as a SampleLogPage (header.extra_channels, total_records,
// torn_tail_bytes and corrupt_record filled in); empty past the end.
using SamplePages = std::function<storage::SampleLogPage(std::uint64_t from, std::size_t count)>;

// A sample as JSON (the API's form, daemon/sample_json.hpp), for the json format.
using SampleJson = std::function<nlohmann::json(const storage::SyncSample&,
                                                std::span<const storage::ChannelInfo>)>;

struct ExportInput {
  std::string run_id;
  SamplePages pages;
  nlohmann::json results;  // results.json; null when the run has none
  nlohmann::json run;      // the run's record (index row / status.json)
  SampleJson sample_json;  // needed for ExportFormat::kJson only
  std::size_t page_records = 20000;
  // The run was still running when exported (only part of its samples): every format says so.
  bool partial = false;
};

struct ExportSummary {
  std::filesystem::path file;
  std::uint64_t samples = 0;
  bool torn_tail = false;       // the log ends in a torn record (ignored)
  bool corrupt_record = false;  // a record failed its checksum; exported up to it
  bool partial = false;         // ExportInput::partial
};

// Writes dir / samples_file_name(format) atomically (a temporary file beside it, renamed over
// it once complete and synced). Throws std::runtime_error naming the file and what failed; no
// temporary file is left behind.
ExportSummary export_samples(const ExportInput& input, ExportFormat format,
                             const std::filesystem::path& dir);

// The log at `path` as SamplePages.
SamplePages sample_log_pages(const std::filesystem::path& path);

}  // namespace wavebench::exports
