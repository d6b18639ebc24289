#include "wavebench/exports/run_export.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <memory>
#include <stdexcept>
#include <system_error>
#include <vector>

#include "export_writers.hpp"
#include "wavebench/exports/export_folder.hpp"

namespace wavebench::exports {

namespace fs = std::filesystem;

namespace {

void write_text(const fs::path& file, const std::string& text) {
  const int fd = ::open(file.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0)
    throw std::system_error(errno, std::generic_category(), "cannot create " + file.string());
  std::size_t done = 0;
  while (done < text.size()) {
    const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      const int e = n < 0 ? errno : ENOSPC;
      ::close(fd);
      throw std::system_error(e, std::generic_category(), "cannot write " + file.string());
    }
    done += static_cast<std::size_t>(n);
  }
  if (::close(fd) != 0) {
    throw std::system_error(errno, std::generic_category(), "cannot write " + file.string());
  }
}

}  // namespace

bool run_still_running(const nlohmann::json& run) {
  return run.is_object() && run.contains("status") && run["status"] == "running";
}

std::optional<std::string> running_run_refusal(const nlohmann::json& run, bool allow_partial,
                                               const std::string& flag) {
  if (allow_partial || !run_still_running(run)) return std::nullopt;
  return "the run is still running: its samples are still being written and an export now "
         "holds only part of them; export it when it has ended, or give " +
         flag + " for a partial export marked as such";
}

ExportSummary export_run(ExportInput input, ExportFormat format, const fs::path& dir,
                         bool allow_partial) {
  if (const auto refusal = running_run_refusal(input.run, allow_partial, "--partial")) {
    throw std::runtime_error("export " + input.run_id + ": " + *refusal);
  }
  input.partial = run_still_running(input.run);
  const bool fresh = prepare_export_folder(dir, input.run_id);
  std::vector<fs::path> committed;
  try {
    ExportSummary summary;
    summary.file = dir / samples_file_name(format);
    PendingFile samples(summary.file);
    const auto walk = detail::write_samples_file(input, format, samples.temp(), summary.file);
    PendingFile run_file(dir / "run.json");
    write_text(run_file.temp(), detail::json_text(input.run) + "\n");
    std::unique_ptr<PendingFile> results_file;
    if (!input.results.is_null()) {
      results_file = std::make_unique<PendingFile>(dir / "results.json");
      write_text(results_file->temp(), detail::json_text(input.results) + "\n");
    }
    // Everything is written and synced before the first name changes.
    samples.commit();
    committed.push_back(samples.target());
    run_file.commit();
    committed.push_back(run_file.target());
    if (results_file) {
      results_file->commit();
      committed.push_back(results_file->target());
    }
    summary.samples = walk.samples;
    summary.torn_tail = walk.torn_tail;
    summary.corrupt_record = walk.corrupt_record;
    summary.partial = input.partial;
    return summary;
  } catch (...) {
    if (fresh) {
      std::error_code ec;
      for (const auto& file : committed) fs::remove(file, ec);
      remove_export_folder_if_bare(dir);
    }
    throw;
  }
}

}  // namespace wavebench::exports
