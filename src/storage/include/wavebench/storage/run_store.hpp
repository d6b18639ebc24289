#pragma once
// Runs on disk: one folder per run under a root, and a SQLite index of all runs.
//
//   <root>/index.sqlite
//   <root>/<run id>/config.yaml     the config text the run started with
//   <root>/<run id>/samples.wbs     SampleLog, written as acquired
//   <root>/<run id>/results.json    written atomically
//   <root>/<run id>/status.json     written atomically at every status change
//
// Run ids are UTC timestamps with microseconds ("20261122T045843.123456Z"): they sort by
// start time, and creating the folder claims the id, so two stores never share one.

#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "wavebench/storage/writer_lock.hpp"

struct sqlite3;

namespace wavebench::storage {

enum class RunStatus { kRunning, kComplete, kAborted, kIncomplete };
const char* run_status_name(RunStatus status);
// Throws std::invalid_argument naming the value and the names expected.
RunStatus parse_run_status(const std::string& name);

struct RunRecord {
  std::string id;
  std::string started_at;   // ISO 8601 UTC
  std::string finished_at;  // empty while running or when incomplete
  std::string unit_serial;
  std::string procedure;
  RunStatus status = RunStatus::kRunning;
  std::string reason;
  std::optional<bool> pass;  // acceptance: passed, failed, none (no limit applied, not complete)
  // "PASS", "FAIL", "UNDECIDED" (a limit inside a figure's uncertainty interval; `pass` then
  // says how the spec counts it), or empty (none, or a row from before this column).
  std::string verdict;
  std::string limits_json = "{}";
  std::string spec;  // the product spec the run was accepted against; empty: none
  std::string software_version;
  std::string config_hash;  // SHA-256 of the config text, hex
};

enum class RunVerdict { kPass, kFail, kNone, kUndecided };

struct RunQuery {
  std::optional<std::string> procedure;
  std::optional<std::string> unit_serial;         // exactly this unit
  std::optional<std::string> unit_serial_prefix;  // units whose serial starts with it
  std::optional<RunStatus> status;
  std::optional<std::string> spec;
  std::optional<RunVerdict> verdict;
  // Run ids (UTC start times) from and to, inclusive: a prefix of an id bounds by it, e.g.
  // from "20261124" to "20261124~" is every run started on 2026-11-24.
  std::optional<std::string> from_id, to_id;
  int limit = 0;  // 0 = all; newest first
  int offset = 0;
};

struct RunPaths {
  std::filesystem::path dir, config, samples, results, status;
};

// The store's own files in its root beside the run folders: the index (and SQLite's -wal and
// -shm beside it) and the file naming the writer's process (the lock is the folder's).
inline constexpr const char* kRunIndexFile = "index.sqlite";

// Not copyable: owns the SQLite connection. One writing process per root: recover() marks every
// `running` run `incomplete`, which would end a live run of another process, so the store holds
// the root's WriterLock (writer_lock.hpp: a flock on the folder itself) while it lives. Stores
// of one process share it; the kernel drops it when the process dies.
class RunStore {
 public:
  // Creates the root and the index if missing, then recover(). Throws RunStoreInUse naming the
  // process that holds the root, std::runtime_error naming the path and SQLite's message.
  RunStore(std::filesystem::path root, std::string software_version);
  ~RunStore();
  RunStore(const RunStore&) = delete;
  RunStore& operator=(const RunStore&) = delete;

  // Claims a new id, writes the config copy and status, indexes the run as running. When a
  // step fails (disk full, read-only, index locked) it removes what it created and rethrows:
  // no folder without an index row.
  std::string create_run(const std::string& procedure, const std::string& unit_serial,
                         const std::string& config_text, const std::string& limits_json = "{}",
                         const std::string& spec = {});
  void write_results(const std::string& id, const nlohmann::json& results);
  // status is kComplete or kAborted; throws std::invalid_argument for an unknown id. The
  // index is updated first; status.json is rewritten where it still can be, in place when no
  // new file can be made beside it (a full disk does not make this throw once the index holds
  // the status). Returns why status.json could not be rewritten; empty when it was.
  // `verdict` is "PASS", "FAIL" or "UNDECIDED"; empty: from `pass` (PASS, FAIL or none).
  std::string finish_run(const std::string& id, RunStatus status, const std::string& reason = {},
                         std::optional<bool> pass = std::nullopt, const std::string& verdict = {});
  // status.json as finish_run() will record the run, the index row left `running`: for the
  // run's report, which reads the folder, before the index says the run ended (its end is
  // recorded only once every file of its results is on disk). Throws std::system_error naming
  // the path, std::invalid_argument as finish_run().
  void write_finished_status(const std::string& id, RunStatus status, const std::string& reason,
                             std::optional<bool> pass, const std::string& verdict) const;
  // Marks every run left `running` as `incomplete`; returns their ids.
  std::vector<std::string> recover();

  std::optional<RunRecord> find_run(const std::string& id) const;
  std::vector<RunRecord> list_runs(const RunQuery& query = {}) const;
  // How many runs match `query`, regardless of its limit and offset.
  std::size_t count_runs(const RunQuery& query = {}) const;
  RunPaths paths(const std::string& id) const;
  const std::filesystem::path& root() const { return root_; }

 private:
  void write_status_file(const RunRecord& run) const;
  RunRecord as_finished(const std::string& id, RunStatus status, const std::string& reason,
                        std::optional<bool> pass, const std::string& verdict) const;
  std::string claim_id();

  std::filesystem::path root_;
  std::string software_version_;
  std::unique_ptr<WriterLock> lock_;
  sqlite3* db_ = nullptr;
  std::string last_id_;
};

nlohmann::json to_json(const RunRecord& run);

}  // namespace wavebench::storage
