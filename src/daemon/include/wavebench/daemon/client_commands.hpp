#pragma once
// What `wavebench status|start|abort|stop|reset|runs|export` do against the daemon, apart
// from the command-line parsing (src/cli/daemon_client_commands.cpp), so tests can run them.
// Each returns the exit status: 0 ok, 1 runtime failure (no daemon, refused, run not
// complete), 2 bad input.

#include <chrono>
#include <filesystem>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

namespace wavebench::daemon {

struct ClientContext {
  std::string daemon_url = "http://127.0.0.1:8470";
  std::filesystem::path token_file;  // empty: default_token_file()
  std::ostream* out = nullptr;       // results
  std::ostream* err = nullptr;       // errors and progress
  std::chrono::milliseconds poll_interval{200};
  std::chrono::milliseconds timeout{45000};  // per request, answer included
  std::chrono::milliseconds connect_timeout{5000};
  // How long a read answered 503 "busy" is retried (DaemonClient::retry_busy); 0: not at all.
  std::chrono::milliseconds busy_wait{120000};
};

int client_status(const ClientContext& ctx);
// options: "key=value"; a value that parses as JSON is sent as such (4, [0,60], true), any
// other as a string.
// spec: a product spec's name (GET /api/specs); empty: none.
int client_start(const ClientContext& ctx, const std::string& procedure,
                 const std::vector<std::string>& options, bool wait, const std::string& spec = {});
int client_abort(const ClientContext& ctx);
int client_stop(const ClientContext& ctx);
int client_reset(const ClientContext& ctx);

struct RunsFilter {
  std::optional<std::string> procedure, status, unit;
  int limit = 0;  // 0: the API's default page (50)
  std::optional<std::string> spec, verdict;
};
int client_runs(const ClientContext& ctx, const RunsFilter& filter);
// Writes samples.mat, samples.h5, samples.csv or samples.json (format "mat", "hdf5", "csv",
// "json"; wavebench/exports/sample_export.hpp), results.json and run.json into out_dir
// (default ./RUN_ID): a new or empty folder, or one an export wrote (export_folder.hpp).
// The samples come page by page from the daemon's samples API. A run still running is refused
// (exit 2) unless `partial` (--partial); then the files say they are partial (run_export.hpp).
int client_export(const ClientContext& ctx, const std::string& run_id,
                  const std::filesystem::path& out_dir, const std::string& format,
                  bool partial = false);
// The same without a daemon: the run folder runs_dir/run_id of a run store (`wavebench run
// --out`, the daemon's --runs), its samples.wbs read page by page, status.json as run.json.
// Reads only; the store's index is not opened (a daemon may be writing it).
int local_export(const ClientContext& ctx, const std::filesystem::path& runs_dir,
                 const std::string& run_id, const std::filesystem::path& out_dir,
                 const std::string& format, bool partial = false);

}  // namespace wavebench::daemon
