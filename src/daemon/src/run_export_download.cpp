#include "wavebench/daemon/run_export_download.hpp"

#include <atomic>
#include <fstream>
#include <optional>
#include <span>
#include <sstream>
#include <stdexcept>

#include "wavebench/daemon/sample_json.hpp"
#include "wavebench/exports/export_scratch.hpp"
#include "wavebench/exports/run_export.hpp"
#include "wavebench/exports/sample_export.hpp"
#include "wavebench/storage/sample_csv.hpp"

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

// What a download asks for, from its query. New query flags go here and in
// export_request_from() (one place), then into the export's input.
struct ExportRequest {
  exports::ExportFormat format = exports::ExportFormat::kCsv;
  std::string format_name;
  bool allow_partial = false;  // partial=1: a running run's samples so far, marked partial
};

// Streamed straight from the log (a finished run's; a partial export is built as a file).
bool made_as_text(exports::ExportFormat format) {
  return format == exports::ExportFormat::kCsv || format == exports::ExportFormat::kJson;
}

nlohmann::json json_file_or_null(const fs::path& path) {
  std::ifstream in(path);
  if (!in) return nullptr;
  auto j = nlohmann::json::parse(in, nullptr, false);
  return j.is_discarded() ? nlohmann::json(nullptr) : j;
}

std::optional<ExportRequest> export_request_from(const HttpTarget& target, ApiResponse& refusal) {
  const auto it = target.query.find("format");
  ExportRequest request;
  request.format_name = it == target.query.end() ? "" : it->second;
  const auto format = exports::export_format_from_name(request.format_name);
  if (!format) {
    refusal = api_error(
        400, "bad request",
        "format: got '" + request.format_name + "', expected " + exports::export_format_list());
    return std::nullopt;
  }
  request.format = *format;
  const auto partial = target.query.find("partial");
  const std::string partial_text = partial == target.query.end() ? "0" : partial->second;
  if (partial_text != "0" && partial_text != "1") {
    refusal = api_error(400, "bad request", "partial: got '" + partial_text + "', expected 0 or 1");
    return std::nullopt;
  }
  request.allow_partial = partial_text == "1";
  return request;
}

exports::ExportInput export_input(const storage::RunStore& store, const std::string& id,
                                  const storage::RunRecord& run) {
  const auto paths = store.paths(id);
  exports::ExportInput input;
  input.run_id = id;
  input.run = storage::to_json(run);
  input.partial = exports::run_still_running(input.run);
  input.results = json_file_or_null(paths.results);
  input.pages = exports::sample_log_pages(paths.samples);
  input.sample_json = [](const storage::SyncSample& s,
                         std::span<const storage::ChannelInfo> extra) {
    return sample_to_json(s, extra);
  };
  return input;
}

// csv and json, one page of samples per chunk: the same text export_samples() writes, with
// only one page of it in memory. Stops at the log's end or its first corrupt record.
class SampleTextChunks : public BodyChunks {
 public:
  SampleTextChunks(exports::ExportInput input, exports::ExportFormat format,
                   std::shared_ptr<void> slot)
      : input_(std::move(input)), format_(format), slot_(std::move(slot)) {}

  std::optional<std::string> next() override {
    if (done_) return std::nullopt;
    const auto page = input_.pages(from_, kExportChunkRecords);
    if (page.from != from_) {
      throw std::runtime_error("sample page from " + std::to_string(page.from) + " when record " +
                               std::to_string(from_) + " was asked for");
    }
    from_ += page.samples.size();
    done_ = page.samples.empty() || page.corrupt_record || from_ >= page.total_records;
    std::string text = format_ == exports::ExportFormat::kCsv ? csv(page) : json(page);
    if (text.empty()) return done_ ? std::nullopt : next();
    return text;
  }

 private:
  std::string csv(const storage::SampleLogPage& page) {
    std::ostringstream out;
    storage::write_samples_csv(page.samples, out, page.header.extra_channels);
    std::string rows = std::move(out).str();
    // write_samples_csv starts every call with the header line: only the first chunk keeps it
    // (an empty log: the header alone).
    if (!first_) rows.erase(0, rows.find('\n') + 1);
    first_ = false;
    return rows;
  }

  std::string json(const storage::SampleLogPage& page) {
    std::string text = first_ ? "[" : "";
    for (const auto& s : page.samples) {
      if (!first_sample_) text += ',';
      first_sample_ = false;
      text += input_.sample_json(s, page.header.extra_channels)
                  .dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
    }
    first_ = false;
    if (done_) text += "]\n";
    return text;
  }

  exports::ExportInput input_;
  exports::ExportFormat format_;
  std::shared_ptr<void> slot_;
  std::uint64_t from_ = 0;
  bool first_ = true;
  bool first_sample_ = true;
  bool done_ = false;
};

// A built file, sent in chunks from its open descriptor; its name is gone already.
class OpenFileChunks : public BodyChunks {
 public:
  OpenFileChunks(std::ifstream in, std::shared_ptr<void> slot)
      : in_(std::move(in)), slot_(std::move(slot)) {}

  std::optional<std::string> next() override {
    std::string chunk(kExportFileChunkBytes, '\0');
    in_.read(chunk.data(), static_cast<std::streamsize>(chunk.size()));
    chunk.resize(static_cast<std::size_t>(in_.gcount()));
    if (in_.bad()) throw std::runtime_error("the export's scratch file could not be read");
    if (chunk.empty()) return std::nullopt;
    return chunk;
  }

 private:
  std::ifstream in_;
  std::shared_ptr<void> slot_;
};

// A folder of its own for one download, removed with what is in it when it goes.
class ScratchFolder {
 public:
  explicit ScratchFolder(const fs::path& parent) {
    static std::atomic<unsigned> counter{0};
    path_ = parent / exports::export_scratch_name(counter++);
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

// A .mat or .h5 file holds each sample's columns as 8-byte numbers, about twice a log record's
// bytes; the reserve covers the results and the formats' own overhead.
std::uintmax_t scratch_estimate(std::uintmax_t log_bytes) {
  return 2 * log_bytes + (std::uintmax_t{16} << 20);
}

}  // namespace

ApiResponse run_export_download(const storage::RunStore& store, const std::string& id,
                                const HttpTarget& target, std::shared_ptr<void> slot,
                                const fs::path& scratch_dir) {
  ApiResponse refusal;
  const auto request = export_request_from(target, refusal);
  if (!request) return refusal;
  const auto run = store.find_run(id);
  if (!run) return api_error(404, "not found", "run '" + id + "' is not in the index");
  std::error_code ec;
  const auto log_bytes = fs::file_size(store.paths(id).samples, ec);
  if (ec) return api_error(404, "not found", "run '" + id + "' has no sample log");
  auto input = export_input(store, id, *run);
  // A run still running only with partial=1, and then the file says it is partial.
  if (const auto running =
          exports::running_run_refusal(input.run, request->allow_partial, "partial=1")) {
    return api_error(409, "conflict", "run '" + id + "': " + *running);
  }

  ApiResponse response;
  response.content_type = content_type(request->format);
  const auto file_name = exports::samples_file_name(request->format);
  response.headers.push_back(
      {"Content-Disposition", "attachment; filename=\"" + id + "-" + file_name + "\""});

  // A partial export is made by the export library, which marks it, like mat and hdf5.
  if (made_as_text(request->format) && !input.partial) {
    // The count the log holds now; the body stops early only at a corrupt record.
    response.headers.push_back(
        {"X-Wavebench-Samples", std::to_string(input.pages(0, 1).total_records)});
    response.chunks =
        std::make_shared<SampleTextChunks>(std::move(input), request->format, std::move(slot));
    return response;
  }

  if (log_bytes > kMaxExportDownloadLogBytes) {
    return api_error(413, "too large",
                     "the sample log is " + std::to_string(log_bytes >> 20) + " MiB; " +
                         request->format_name + " downloads take at most " +
                         std::to_string(kMaxExportDownloadLogBytes >> 20) +
                         " MiB (csv and json have no limit); or use 'wavebench export " + id +
                         " --format " + request->format_name + "'");
  }
  const auto parent = scratch_dir.empty() ? fs::temp_directory_path() : scratch_dir;
  const auto space = fs::space(parent, ec);
  const auto needed = scratch_estimate(log_bytes) + kScratchReserveBytes;
  if (ec || space.available < needed) {
    return api_error(507, "insufficient storage",
                     "building the " + request->format_name + " file needs about " +
                         std::to_string(needed >> 20) + " MiB free in " + parent.string() +
                         ", it has " +
                         (ec ? "unknown (" + ec.message() + ")"
                             : std::to_string(space.available >> 20) + " MiB") +
                         "; download csv, or export with 'wavebench export'");
  }
  ScratchFolder scratch(parent);
  const auto summary = exports::export_samples(input, request->format, scratch.path());
  std::ifstream in(summary.file, std::ios::binary);
  if (!in) throw std::runtime_error("cannot open the built export " + summary.file.string());
  // The open file outlives its name: the scratch folder goes now, and the disk space with the
  // last chunk, whatever the client does.
  response.headers.push_back({"X-Wavebench-Samples", std::to_string(summary.samples)});
  response.chunks = std::make_shared<OpenFileChunks>(std::move(in), std::move(slot));
  return response;
}

}  // namespace wavebench::daemon
