// CSV and JSON: the forms `wavebench export` wrote before .mat and HDF5, now one page at a time.
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "export_writers.hpp"
#include "wavebench/storage/sample_csv.hpp"

namespace wavebench::exports::detail {

namespace {

std::ofstream open_new(const std::filesystem::path& file) {
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  if (!out) throw std::runtime_error("cannot create " + file.string());
  return out;
}

void close_checked(std::ofstream& out, const std::filesystem::path& file) {
  out.flush();
  if (!out) throw std::runtime_error("write failed for " + file.string());
  out.close();
}

}  // namespace

PageWalk write_csv_file(const ExportInput& input, const std::filesystem::path& file) {
  auto out = open_new(file);
  // Only a partial export (asked for explicitly) has this line; readers skip it as a comment
  // (pandas comment='#', MATLAB's CommentStyle).
  if (input.partial) {
    out << "# partial export: run "
        << nlohmann::json(input.run_id)
               .dump(-1, ' ', false, nlohmann::json::error_handler_t::replace)
        << " was still running; only the samples logged so far\n";
  }
  bool header = true;
  auto walk = walk_pages(input, [&](const storage::SampleLogPage& page) {
    std::ostringstream text;
    storage::write_samples_csv(page.samples, text, page.header.extra_channels);
    std::string rows = std::move(text).str();
    // write_samples_csv starts every call with the header line: keep the first page's only.
    if (!header) rows.erase(0, rows.find('\n') + 1);
    header = false;
    out << rows;
  });
  if (header) storage::write_samples_csv({}, out, walk.extra);  // an empty log: the header
  close_checked(out, file);
  return walk;
}

PageWalk write_json_file(const ExportInput& input, const std::filesystem::path& file) {
  auto out = open_new(file);
  // A partial export (asked for explicitly) is an object that says so around the list.
  if (input.partial) {
    out << R"({"partial":true,"run_id":)"
        << nlohmann::json(input.run_id)
               .dump(-1, ' ', false, nlohmann::json::error_handler_t::replace)
        << R"(,"samples":)";
  }
  out << '[';
  bool first = true;
  auto walk = walk_pages(input, [&](const storage::SampleLogPage& page) {
    for (const auto& s : page.samples) {
      if (!first) out << ',';
      first = false;
      out << input.sample_json(s, page.header.extra_channels)
                 .dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
    }
  });
  out << (input.partial ? "]}\n" : "]\n");
  close_checked(out, file);
  return walk;
}

}  // namespace wavebench::exports::detail
