#include "wavebench/storage/run_store.hpp"

#include <fcntl.h>
#include <sqlite3.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdint>
#include <ctime>
#include <fstream>
#include <stdexcept>
#include <system_error>
#include <vector>

#include "wavebench/storage/atomic_file.hpp"
#include "wavebench/storage/like_prefix.hpp"
#include "wavebench/storage/sha256.hpp"

namespace wavebench::storage {

namespace {

constexpr const char* kSchema = R"sql(
CREATE TABLE IF NOT EXISTS runs (
  id TEXT PRIMARY KEY,
  started_at TEXT NOT NULL,
  finished_at TEXT,
  unit_serial TEXT NOT NULL,
  procedure TEXT NOT NULL,
  status TEXT NOT NULL CHECK (status IN ('running','complete','aborted','incomplete')),
  reason TEXT NOT NULL DEFAULT '',
  pass INTEGER,
  limits_json TEXT NOT NULL DEFAULT '{}',
  software_version TEXT NOT NULL,
  config_hash TEXT NOT NULL
);
CREATE INDEX IF NOT EXISTS runs_by_unit ON runs(unit_serial, started_at);
CREATE INDEX IF NOT EXISTS runs_by_status ON runs(status);
)sql";

// Added after the first indexes were written: old index files get them on open (migrate()).
constexpr const char* kAddedColumns[][2] = {{"spec", "TEXT NOT NULL DEFAULT ''"},
                                            {"verdict", "TEXT NOT NULL DEFAULT ''"}};

// History pages are newest first (by id) under one filter or two: each filter column leads an
// index that ends in id, so SQLite walks it in order and stops after the page.
constexpr const char* kHistoryIndexes = R"sql(
CREATE INDEX IF NOT EXISTS runs_by_unit_id ON runs(unit_serial, id);
CREATE INDEX IF NOT EXISTS runs_by_procedure_id ON runs(procedure, id);
CREATE INDEX IF NOT EXISTS runs_by_status_id ON runs(status, id);
CREATE INDEX IF NOT EXISTS runs_by_spec_id ON runs(spec, id);
CREATE INDEX IF NOT EXISTS runs_by_pass_id ON runs(pass, id);
)sql";

// Prepared statement that finalizes itself; binds text by index.
class Statement {
 public:
  Statement(sqlite3* db, const std::string& sql) : db_(db) {
    if (sqlite3_prepare_v2(db, sql.c_str(), -1, &stmt_, nullptr) != SQLITE_OK) {
      throw std::runtime_error(std::string("run index: cannot prepare '") + sql +
                               "': " + sqlite3_errmsg(db));
    }
  }
  ~Statement() { sqlite3_finalize(stmt_); }
  Statement(const Statement&) = delete;
  Statement& operator=(const Statement&) = delete;

  void bind(int i, const std::string& text) {
    sqlite3_bind_text(stmt_, i, text.c_str(), static_cast<int>(text.size()), SQLITE_TRANSIENT);
  }
  void bind(int i, std::optional<bool> value) {
    if (value) {
      sqlite3_bind_int(stmt_, i, *value ? 1 : 0);
    } else {
      sqlite3_bind_null(stmt_, i);
    }
  }
  void bind_int(int i, int value) { sqlite3_bind_int(stmt_, i, value); }
  bool step() {
    const int rc = sqlite3_step(stmt_);
    if (rc == SQLITE_ROW) return true;
    if (rc == SQLITE_DONE) return false;
    throw std::runtime_error(std::string("run index: ") + sqlite3_errmsg(db_));
  }
  std::string text(int col) const {
    const auto* p = sqlite3_column_text(stmt_, col);
    return p ? reinterpret_cast<const char*>(p) : "";
  }
  std::int64_t int64(int col) const { return sqlite3_column_int64(stmt_, col); }
  std::optional<bool> optional_bool(int col) const {
    if (sqlite3_column_type(stmt_, col) == SQLITE_NULL) return std::nullopt;
    return sqlite3_column_int(stmt_, col) != 0;
  }

 private:
  sqlite3* db_;
  sqlite3_stmt* stmt_ = nullptr;
};

void exec(sqlite3* db, const char* sql) {
  char* message = nullptr;
  if (sqlite3_exec(db, sql, nullptr, nullptr, &message) != SQLITE_OK) {
    std::string text = message ? message : "unknown error";
    sqlite3_free(message);
    throw std::runtime_error("run index: " + text);
  }
}

std::string format_utc(std::chrono::system_clock::time_point t, bool compact) {
  const auto us = std::chrono::duration_cast<std::chrono::microseconds>(t.time_since_epoch());
  const std::time_t seconds = static_cast<std::time_t>(us.count() / 1000000);
  const long micros = static_cast<long>(us.count() % 1000000);
  std::tm tm{};
  gmtime_r(&seconds, &tm);
  char buf[64];
  const std::size_t n = compact ? std::strftime(buf, sizeof buf, "%Y%m%dT%H%M%S", &tm)
                                : std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%S", &tm);
  char tail[16];
  std::snprintf(tail, sizeof tail, ".%06ldZ", micros);
  return std::string(buf, n) + tail;
}

constexpr const char* kColumns =
    "id, started_at, finished_at, unit_serial, procedure, status, reason, pass, limits_json, "
    "software_version, config_hash, spec, verdict";

RunRecord read_row(const Statement& s) {
  RunRecord r;
  r.id = s.text(0);
  r.started_at = s.text(1);
  r.finished_at = s.text(2);
  r.unit_serial = s.text(3);
  r.procedure = s.text(4);
  r.status = parse_run_status(s.text(5));
  r.reason = s.text(6);
  r.pass = s.optional_bool(7);
  r.limits_json = s.text(8);
  r.software_version = s.text(9);
  r.config_hash = s.text(10);
  r.spec = s.text(11);
  r.verdict = s.text(12);
  return r;
}

bool has_column(sqlite3* db, const std::string& column) {
  Statement s(db, "SELECT 1 FROM pragma_table_info('runs') WHERE name = ?1");
  s.bind(1, column);
  return s.step();
}

void migrate(sqlite3* db) {
  for (const auto& [column, type] : kAddedColumns) {
    if (!has_column(db, column)) {
      exec(db, (std::string("ALTER TABLE runs ADD COLUMN ") + column + " " + type).c_str());
    }
  }
  exec(db, kHistoryIndexes);
}

// The WHERE clause of a query with only the filters it sets (so that SQLite can pick the
// index of one), and their values in parameter order.
struct Filters {
  std::string where;
  std::vector<std::string> values;
};

Filters filters_of(const RunQuery& q) {
  Filters f;
  const auto add = [&](const char* condition, const std::optional<std::string>& value) {
    if (!value) return;
    f.where += (f.where.empty() ? " WHERE " : " AND ") + std::string(condition);
    f.values.push_back(*value);
  };
  add("procedure = ?", q.procedure);
  add("unit_serial = ?", q.unit_serial);
  if (q.unit_serial_prefix) {
    add((std::string("unit_serial LIKE ?") + kLikeEscapeClause).c_str(),
        like_prefix_pattern(*q.unit_serial_prefix));
  }
  if (q.status) add("status = ?", std::string(run_status_name(*q.status)));
  add("spec = ?", q.spec);
  add("id >= ?", q.from_id);
  add("id <= ?", q.to_id);
  if (q.verdict) {
    f.where += f.where.empty() ? " WHERE " : " AND ";
    // By the verdict shown; rows from before the verdict column have only `pass`.
    f.where +=
        *q.verdict == RunVerdict::kNone   ? "(pass IS NULL AND verdict = '')"
        : *q.verdict == RunVerdict::kPass ? "(verdict = 'PASS' OR (verdict = '' AND pass = 1))"
        : *q.verdict == RunVerdict::kFail ? "(verdict = 'FAIL' OR (verdict = '' AND pass = 0))"
                                          : "verdict = 'UNDECIDED'";
  }
  return f;
}

void bind_filters(Statement& s, const Filters& f) {
  for (std::size_t i = 0; i < f.values.size(); ++i) s.bind(static_cast<int>(i + 1), f.values[i]);
}

}  // namespace

const char* run_status_name(RunStatus status) {
  switch (status) {
    case RunStatus::kRunning:
      return "running";
    case RunStatus::kComplete:
      return "complete";
    case RunStatus::kAborted:
      return "aborted";
    case RunStatus::kIncomplete:
      return "incomplete";
  }
  return "?";
}

RunStatus parse_run_status(const std::string& name) {
  for (auto s :
       {RunStatus::kRunning, RunStatus::kComplete, RunStatus::kAborted, RunStatus::kIncomplete}) {
    if (name == run_status_name(s)) return s;
  }
  throw std::invalid_argument("run status: '" + name +
                              "'; expected running, complete, aborted or incomplete");
}

nlohmann::json to_json(const RunRecord& run) {
  nlohmann::json j = {{"id", run.id},
                      {"started_at", run.started_at},
                      {"finished_at", run.finished_at},
                      {"unit_serial", run.unit_serial},
                      {"procedure", run.procedure},
                      {"status", run_status_name(run.status)},
                      {"reason", run.reason},
                      {"limits", nlohmann::json::parse(run.limits_json, nullptr, false)},
                      {"software_version", run.software_version},
                      {"config_hash", run.config_hash}};
  j["spec"] = run.spec.empty() ? nlohmann::json(nullptr) : nlohmann::json(run.spec);
  j["verdict"] = !run.verdict.empty() ? nlohmann::json(run.verdict)
                 : run.pass           ? nlohmann::json(*run.pass ? "PASS" : "FAIL")
                                      : nlohmann::json(nullptr);
  j["pass"] = run.pass ? nlohmann::json(*run.pass) : nlohmann::json(nullptr);
  return j;
}

RunStore::RunStore(std::filesystem::path root, std::string software_version)
    : root_(std::move(root)), software_version_(std::move(software_version)) {
  std::filesystem::create_directories(root_);
  lock_ = std::make_unique<WriterLock>(root_);
  const auto db_path = root_ / "index.sqlite";
  if (sqlite3_open_v2(db_path.c_str(), &db_,
                      SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE | SQLITE_OPEN_FULLMUTEX,
                      nullptr) != SQLITE_OK) {
    std::string message = db_ ? sqlite3_errmsg(db_) : "out of memory";
    sqlite3_close(db_);
    db_ = nullptr;
    throw std::runtime_error("run index: cannot open " + db_path.string() + ": " + message);
  }
  sqlite3_busy_timeout(db_, 5000);
  exec(db_, "PRAGMA journal_mode=WAL; PRAGMA synchronous=FULL;");
  exec(db_, kSchema);
  migrate(db_);
  recover();
}

RunStore::~RunStore() {
  sqlite3_close(db_);
}

RunPaths RunStore::paths(const std::string& id) const {
  RunPaths p;
  p.dir = root_ / id;
  p.config = p.dir / "config.yaml";
  p.samples = p.dir / "samples.wbs";
  p.results = p.dir / "results.json";
  p.status = p.dir / "status.json";
  return p;
}

std::string RunStore::claim_id() {
  auto t = std::chrono::system_clock::now();
  for (int attempt = 0; attempt < 100000; ++attempt) {
    std::string id = format_utc(t, true);
    // Same-microsecond or clock-stepped-back ids move forward so ids stay sortable.
    if (id <= last_id_) {
      t += std::chrono::microseconds(1);
      continue;
    }
    const auto dir = root_ / id;
    if (::mkdir(dir.c_str(), 0755) == 0) {
      last_id_ = id;
      return id;
    }
    if (errno != EEXIST) {
      throw std::system_error(errno, std::generic_category(), "run store: mkdir " + dir.string());
    }
    t += std::chrono::microseconds(1);
  }
  throw std::runtime_error("run store: no free run id under " + root_.string());
}

std::string RunStore::create_run(const std::string& procedure, const std::string& unit_serial,
                                 const std::string& config_text, const std::string& limits_json,
                                 const std::string& spec) {
  if (!nlohmann::json::accept(limits_json)) {
    throw std::invalid_argument("run store: limits_json = '" + limits_json +
                                "' is not JSON; expected an object");
  }
  RunRecord run;
  run.id = claim_id();
  run.started_at = format_utc(std::chrono::system_clock::now(), false);
  run.unit_serial = unit_serial;
  run.procedure = procedure;
  run.status = RunStatus::kRunning;
  run.limits_json = limits_json;
  run.software_version = software_version_;
  run.config_hash = sha256_hex(config_text);
  run.spec = spec;
  const auto p = paths(run.id);
  try {
    write_file_atomically(p.config, config_text);
    write_status_file(run);

    Statement s(db_,
                std::string("INSERT INTO runs (") + kColumns +
                    ") VALUES (?1, ?2, NULL, ?3, ?4, 'running', '', NULL, ?5, ?6, ?7, ?8, '')");
    s.bind(1, run.id);
    s.bind(2, run.started_at);
    s.bind(3, run.unit_serial);
    s.bind(4, run.procedure);
    s.bind(5, run.limits_json);
    s.bind(6, run.software_version);
    s.bind(7, run.config_hash);
    s.bind(8, run.spec);
    s.step();
  } catch (...) {
    // No orphan folder (a full disk would otherwise collect one per refused start), and only
    // what this call wrote: the folder is fresh from claim_id(), rmdir() removes it only empty.
    std::error_code ignored;
    std::filesystem::remove(p.status, ignored);
    std::filesystem::remove(p.config, ignored);
    ::rmdir(p.dir.c_str());
    throw;
  }
  return run.id;
}

void RunStore::write_results(const std::string& id, const nlohmann::json& results) {
  if (!find_run(id)) throw std::invalid_argument("run store: run id '" + id + "' is not indexed");
  write_file_atomically(paths(id).results, results.dump(2) + "\n");
}

RunRecord RunStore::as_finished(const std::string& id, RunStatus status, const std::string& reason,
                                std::optional<bool> pass, const std::string& verdict) const {
  if (status != RunStatus::kComplete && status != RunStatus::kAborted) {
    throw std::invalid_argument(std::string("run store: finish status '") +
                                run_status_name(status) + "'; expected complete or aborted");
  }
  auto run = find_run(id);
  if (!run) throw std::invalid_argument("run store: run id '" + id + "' is not indexed");
  run->status = status;
  run->reason = reason;
  run->pass = pass;
  run->finished_at = format_utc(std::chrono::system_clock::now(), false);
  run->verdict = verdict.empty() && pass ? std::string(*pass ? "PASS" : "FAIL") : verdict;
  return *run;
}

void RunStore::write_finished_status(const std::string& id, RunStatus status,
                                     const std::string& reason, std::optional<bool> pass,
                                     const std::string& verdict) const {
  write_status_file(as_finished(id, status, reason, pass, verdict));
}

std::string RunStore::finish_run(const std::string& id, RunStatus status, const std::string& reason,
                                 std::optional<bool> pass, const std::string& verdict) {
  const RunRecord run = as_finished(id, status, reason, pass, verdict);
  Statement s(db_,
              "UPDATE runs SET status = ?2, reason = ?3, pass = ?4, finished_at = ?5, verdict = ?6 "
              "WHERE id = ?1");
  s.bind(1, id);
  s.bind(2, std::string(run_status_name(run.status)));
  s.bind(3, run.reason);
  s.bind(4, run.pass);
  s.bind(5, run.finished_at);
  s.bind(6, run.verdict);
  s.step();
  if (sqlite3_changes(db_) != 1) {
    throw std::invalid_argument("run store: run id '" + id + "' is not indexed");
  }
  // The index row is the record; status.json is its copy for readers of the folder, and a
  // full disk must not turn a finished run back into an exception.
  try {
    write_status_file(*find_run(id));
  } catch (const std::system_error& e) {
    return e.what();
  }
  return {};
}

std::vector<std::string> RunStore::recover() {
  RunQuery q;
  q.status = RunStatus::kRunning;
  std::vector<std::string> ids;
  for (const auto& run : list_runs(q)) {
    Statement s(db_,
                "UPDATE runs SET status = 'incomplete', reason = ?2 WHERE id = ?1 AND "
                "status = 'running'");
    s.bind(1, run.id);
    s.bind(2, std::string("the process ended while the run was running"));
    s.step();
    if (auto updated = find_run(run.id); updated && std::filesystem::exists(paths(run.id).dir)) {
      try {
        write_status_file(*updated);
      } catch (const std::system_error&) {  // NOLINT(bugprone-empty-catch)
        // A folder that cannot be written any more (read-only, immutable) must not keep the
        // store from opening: the index holds the status.
      }
    }
    ids.push_back(run.id);
  }
  return ids;
}

std::optional<RunRecord> RunStore::find_run(const std::string& id) const {
  Statement s(db_, std::string("SELECT ") + kColumns + " FROM runs WHERE id = ?1");
  s.bind(1, id);
  if (!s.step()) return std::nullopt;
  return read_row(s);
}

std::vector<RunRecord> RunStore::list_runs(const RunQuery& query) const {
  const Filters filters = filters_of(query);
  std::string sql =
      std::string("SELECT ") + kColumns + " FROM runs" + filters.where + " ORDER BY id DESC";
  if (query.limit > 0 || query.offset > 0) {
    sql += " LIMIT " + std::to_string(query.limit > 0 ? query.limit : -1) + " OFFSET " +
           std::to_string(std::max(query.offset, 0));
  }
  Statement s(db_, sql);
  bind_filters(s, filters);
  std::vector<RunRecord> out;
  while (s.step()) out.push_back(read_row(s));
  return out;
}

std::size_t RunStore::count_runs(const RunQuery& query) const {
  const Filters filters = filters_of(query);
  Statement s(db_, std::string("SELECT COUNT(*) FROM runs") + filters.where);
  bind_filters(s, filters);
  s.step();
  return static_cast<std::size_t>(s.int64(0));
}

void RunStore::write_status_file(const RunRecord& run) const {
  const auto file = paths(run.id).status;
  const std::string text = to_json(run).dump(2) + "\n";
  try {
    write_file_atomically(file, text);
  } catch (const std::system_error& atomic) {
    // No new file beside it (a folder made read-only, a full disk): the old one must still not
    // go on saying `running` once the index says otherwise.
    try {
      overwrite_file_in_place(file, text);
    } catch (const std::system_error& in_place) {
      throw std::system_error(atomic.code(), std::string(atomic.what()) + "; " + in_place.what());
    }
  }
}

}  // namespace wavebench::storage
