#include "wavebench/exports/sample_export.hpp"

#include <algorithm>
#include <stdexcept>

#include "export_writers.hpp"
#include "wavebench/exports/export_folder.hpp"

namespace wavebench::exports {

namespace detail {

std::vector<storage::ChannelInfo> extra_channels_of(const ExportInput& input) {
  return input.pages(0, 1).header.extra_channels;
}

PageWalk walk_pages(const ExportInput& input,
                    const std::function<void(const storage::SampleLogPage&)>& visit) {
  PageWalk walk;
  const std::size_t count = std::max<std::size_t>(1, input.page_records);
  std::uint64_t from = 0;
  for (bool first = true;; first = false) {
    const auto page = input.pages(from, count);
    if (first) walk.extra = page.header.extra_channels;
    if (page.from != from) {
      throw std::runtime_error("sample page from " + std::to_string(page.from) + " when record " +
                               std::to_string(from) + " was asked for");
    }
    walk.torn_tail = page.torn_tail_bytes > 0;
    walk.corrupt_record = walk.corrupt_record || page.corrupt_record;
    if (!page.samples.empty()) visit(page);
    from += page.samples.size();
    walk.samples = from;
    if (page.samples.empty() || page.corrupt_record || from >= page.total_records) break;
  }
  return walk;
}

std::string json_text(const nlohmann::json& j, bool ascii) {
  return j.dump(2, ' ', ascii, nlohmann::json::error_handler_t::replace);
}

std::string field_name(const std::string& key) {
  std::string out;
  for (const char c : key) {
    const bool keep = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9');
    out += keep ? c : '_';
  }
  if (out.empty()) return out;
  if (!((out[0] >= 'a' && out[0] <= 'z') || (out[0] >= 'A' && out[0] <= 'Z'))) out = "x" + out;
  if (out.size() > 63) out.resize(63);
  return out;
}

PageWalk write_samples_file(const ExportInput& input, ExportFormat format,
                            const std::filesystem::path& file,
                            const std::filesystem::path& target) {
  if (!input.pages) throw std::invalid_argument("export: no sample pages given");
  try {
    switch (format) {
      case ExportFormat::kMat:
        return write_mat_file(input, file);
      case ExportFormat::kHdf5:
        return write_hdf5_file(input, file);
      case ExportFormat::kCsv:
        return write_csv_file(input, file);
      case ExportFormat::kJson:
        if (!input.sample_json) throw std::invalid_argument("export: no sample JSON form given");
        return write_json_file(input, file);
    }
  } catch (const std::exception& e) {
    // Named by the file the user asked for, not its temporary name.
    throw std::runtime_error(target.string() + ": " + e.what());
  }
  throw std::logic_error("export format");
}

}  // namespace detail

ExportSummary export_samples(const ExportInput& input, ExportFormat format,
                             const std::filesystem::path& dir) {
  ExportSummary summary;
  summary.file = dir / samples_file_name(format);
  PendingFile pending(summary.file);
  const auto walk = detail::write_samples_file(input, format, pending.temp(), summary.file);
  pending.commit();
  summary.partial = input.partial;
  summary.samples = walk.samples;
  summary.torn_tail = walk.torn_tail;
  summary.corrupt_record = walk.corrupt_record;
  return summary;
}

SamplePages sample_log_pages(const std::filesystem::path& path) {
  return [path](std::uint64_t from, std::size_t count) {
    return storage::read_sample_log_page(path, from, count);
  };
}

}  // namespace wavebench::exports
