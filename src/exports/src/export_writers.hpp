#pragma once
// The writers behind export_samples(), one per format, and the page walk they share.

#include <cstdint>
#include <filesystem>
#include <functional>
#include <vector>

#include "wavebench/exports/sample_export.hpp"

namespace wavebench::exports::detail {

struct PageWalk {
  std::vector<storage::ChannelInfo> extra;  // the log's extra channels
  std::uint64_t samples = 0;
  bool torn_tail = false;
  bool corrupt_record = false;
};

// The log's header (its extra channels) from a one-record page.
std::vector<storage::ChannelInfo> extra_channels_of(const ExportInput& input);

// visit(page) for each non-empty page in order, up to the end of the log or its first corrupt
// record. Throws std::runtime_error when a page does not start where asked.
PageWalk walk_pages(const ExportInput& input,
                    const std::function<void(const storage::SampleLogPage&)>& visit);

// Each writes `file` (a new file) and returns the walk of its last pass over the pages.
PageWalk write_mat_file(const ExportInput& input, const std::filesystem::path& file);
PageWalk write_hdf5_file(const ExportInput& input, const std::filesystem::path& file);
PageWalk write_csv_file(const ExportInput& input, const std::filesystem::path& file);
PageWalk write_json_file(const ExportInput& input, const std::filesystem::path& file);

// The samples in `format` into `file` (a new file, not renamed anywhere); errors name
// `target`, the name it is written for.
PageWalk write_samples_file(const ExportInput& input, ExportFormat format,
                            const std::filesystem::path& file, const std::filesystem::path& target);

// `j` as indented text; bytes that are not UTF-8 (a hostile run record) become U+FFFD instead
// of an exception mid-export. `ascii`: non-ASCII as \u escapes (MAT 5 char data is 8-bit).
std::string json_text(const nlohmann::json& j, bool ascii = false);

// A results key as a MATLAB identifier / HDF5 link name: [A-Za-z0-9_], a letter first, at most
// 63 characters; empty when nothing of it is left.
std::string field_name(const std::string& key);

}  // namespace wavebench::exports::detail
