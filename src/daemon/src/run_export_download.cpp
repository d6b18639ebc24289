#include "wavebench/daemon/run_export_download.hpp"

#include <unistd.h>

#include <atomic>
#include <fstream>
#include <span>
#include <sstream>

#include "wavebench/daemon/sample_json.hpp"
#include "wavebench/exports/export_scratch.hpp"
#include "wavebench/exports/run_export.hpp"
#include "wavebench/exports/sample_export.hpp"

namespace wavebench::daemon {

namespace {

namespace fs = std::filesystem;

const char* content_type(exports::ExportFormat format) {
  switch (format) {
    case exports::ExportFormat::kMat:
      return "application/x-matlab-data";
    case exports::ExportFormat::kHdf5:
      return "application/x-hdf5";
    case exports::ExportFormat::kCsv:
      return "text/csv; charset=utf-8";
    case exports::ExportFormat::kJson:
      return "application/json";
  }
  return "application/octet-stream";
}

nlohmann::json json_file_or_null(const fs::path& path) {
  std::ifstream in(path);
  if (!in) return nullptr;
  auto j = nlohmann::json::parse(in, nullptr, false);
  return j.is_discarded() ? nlohmann::json(nullptr) : j;
}

// A folder of its own for one download, removed with what is in it when the answer is read.
class ScratchFolder {
 public:
  ScratchFolder() {
    static std::atomic<unsigned> counter{0};
    path_ = fs::temp_directory_path() / exports::export_scratch_name(counter++);
    fs::create_directories(path_);
  }
  ~ScratchFolder() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  ScratchFolder(const ScratchFolder&) = delete;
  ScratchFolder& operator=(const ScratchFolder&) = delete;
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

}  // namespace

ApiResponse run_export_download(const storage::RunStore& store, const std::string& id,
                                const HttpTarget& target) {
  const auto it = target.query.find("format");
  const std::string name = it == target.query.end() ? "" : it->second;
  const auto format = exports::export_format_from_name(name);
  if (!format) {
    return api_error(400, "bad request",
                     "format: got '" + name + "', expected " + exports::export_format_list());
  }
  const auto run = store.find_run(id);
  if (!run) return api_error(404, "not found", "run '" + id + "' is not in the index");
  // A run still running only with partial=1, and then the file says it is partial.
  const auto partial_it = target.query.find("partial");
  const std::string partial_text = partial_it == target.query.end() ? "0" : partial_it->second;
  if (partial_text != "0" && partial_text != "1") {
    return api_error(400, "bad request", "partial: got '" + partial_text + "', expected 0 or 1");
  }
  const auto run_json = storage::to_json(*run);
  if (const auto refusal =
          exports::running_run_refusal(run_json, partial_text == "1", "partial=1")) {
    return api_error(409, "conflict", "run '" + id + "': " + *refusal);
  }
  const auto paths = store.paths(id);
  std::error_code ec;
  const auto log_bytes = fs::file_size(paths.samples, ec);
  if (ec) return api_error(404, "not found", "run '" + id + "' has no sample log");
  if (log_bytes > kMaxExportDownloadLogBytes) {
    return api_error(
        413, "too large",
        "the sample log is " + std::to_string(log_bytes >> 20) + " MiB, downloads take at most " +
            std::to_string(kMaxExportDownloadLogBytes >> 20) + " MiB; use 'wavebench export " + id +
            " --format " + name + "', which pages through the samples API");
  }
  exports::ExportInput input;
  input.run_id = id;
  input.run = run_json;
  input.partial = exports::run_still_running(run_json);
  input.results = json_file_or_null(paths.results);
  input.pages = exports::sample_log_pages(paths.samples);
  input.sample_json = [](const storage::SyncSample& s,
                         std::span<const storage::ChannelInfo> extra) {
    return sample_to_json(s, extra);
  };
  ScratchFolder scratch;
  const auto summary = exports::export_samples(input, *format, scratch.path());
  std::ifstream in(summary.file, std::ios::binary);
  std::ostringstream bytes;
  bytes << in.rdbuf();
  ApiResponse response;
  response.raw_body = std::move(bytes).str();
  response.content_type = content_type(*format);
  response.headers.push_back({"Content-Disposition", "attachment; filename=\"" + id + "-" +
                                                         summary.file.filename().string() + "\""});
  response.headers.push_back({"X-Wavebench-Samples", std::to_string(summary.samples)});
  return response;
}

}  // namespace wavebench::daemon
