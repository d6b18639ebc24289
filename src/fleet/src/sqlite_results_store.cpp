#include "wavebench/fleet/sqlite_results_store.hpp"

#include <sqlite3.h>

#include <array>
#include <cmath>
#include <stdexcept>

#include "figure_columns.hpp"
#include "figure_query_rules.hpp"
#include "fleet_sql.hpp"
#include "sqlite_statement.hpp"
#include "wavebench/fleet/fleet_figures.hpp"
#include "wavebench/fleet/utc_time_text.hpp"

namespace wavebench::fleet {

namespace {

// The PostgreSQL schema's tables (schema_migrations.cpp) in SQLite's types: times as
// canonical_utc() text, which sorts as the times do. Never edit a migration once released.
constexpr std::array<const char*, 1> kMigrations = {R"sql(
CREATE TABLE fleet_runs (
  bench TEXT NOT NULL,
  run_id TEXT NOT NULL,
  station TEXT NOT NULL DEFAULT '',
  operator TEXT,
  unit_serial TEXT NOT NULL,
  gear_model TEXT NOT NULL DEFAULT '',
  spec TEXT NOT NULL DEFAULT '',
  spec_version TEXT NOT NULL DEFAULT '',
  procedure TEXT NOT NULL,
  status TEXT NOT NULL,
  reason TEXT NOT NULL DEFAULT '',
  verdict TEXT,
  pass INTEGER,
  started_at TEXT NOT NULL,
  finished_at TEXT,
  software_version TEXT NOT NULL,
  config_hash TEXT NOT NULL,
  samples_ref TEXT NOT NULL,
  static_p2p_arcmin REAL,
  static_lost_motion_arcmin REAL,
  lost_motion_arcmin REAL,
  k1_nm_per_rad REAL,
  k2_nm_per_rad REAL,
  k3_nm_per_rad REAL,
  dynamic_p2p_arcsec REAL,
  dynamic_rms_arcsec REAL,
  twin_residual_before_arcsec REAL,
  twin_residual_after_arcsec REAL,
  limits TEXT NOT NULL DEFAULT '{}',
  results TEXT NOT NULL DEFAULT '{}',
  published_at TEXT NOT NULL DEFAULT (strftime('%Y-%m-%dT%H:%M:%fZ', 'now')),
  PRIMARY KEY (bench, run_id)
);
CREATE INDEX fleet_runs_by_model ON fleet_runs (gear_model, started_at);
CREATE INDEX fleet_runs_by_started ON fleet_runs (started_at);
CREATE INDEX fleet_runs_by_unit ON fleet_runs (unit_serial, started_at);
CREATE TABLE fleet_static_passes (
  bench TEXT NOT NULL,
  run_id TEXT NOT NULL,
  direction TEXT NOT NULL,
  load_nm REAL NOT NULL,
  p2p_arcmin REAL,
  mean_arcmin REAL,
  std_arcmin REAL,
  PRIMARY KEY (bench, run_id, direction, load_nm),
  FOREIGN KEY (bench, run_id) REFERENCES fleet_runs (bench, run_id) ON DELETE CASCADE
);
)sql"};

void exec(sqlite3* db, const std::string& sql) {
  char* message = nullptr;
  if (sqlite3_exec(db, sql.c_str(), nullptr, nullptr, &message) != SQLITE_OK) {
    std::string text = message ? message : "unknown error";
    sqlite3_free(message);
    throw std::runtime_error("sqlite results store: " + text);
  }
}

// BEGIN IMMEDIATE ... COMMIT, rolled back when `work` throws.
template <typename Work>
void transaction(sqlite3* db, Work work) {
  exec(db, "BEGIN IMMEDIATE");
  try {
    work();
    exec(db, "COMMIT");
  } catch (...) {
    sqlite3_exec(db, "ROLLBACK", nullptr, nullptr, nullptr);
    throw;
  }
}

bool has_table(sqlite3* db, const char* name) {
  SqliteStatement s(db, "SELECT 1 FROM sqlite_master WHERE type = 'table' AND name = ?1");
  s.bind(1, std::string(name));
  return s.step();
}

int current_version(sqlite3* db) {
  if (!has_table(db, "fleet_schema_version")) return 0;
  SqliteStatement s(db, "SELECT COALESCE(MAX(version), 0) FROM fleet_schema_version");
  s.step();
  return static_cast<int>(s.number(0).value_or(0));
}

ColumnSet run_columns(sqlite3* db) {
  ColumnSet present;
  SqliteStatement s(db, "SELECT name FROM pragma_table_info('fleet_runs')");
  while (s.step()) present.insert(s.text(0));
  return present;
}

void migrate(sqlite3* db) {
  transaction(db, [&] {
    exec(db,
         "CREATE TABLE IF NOT EXISTS fleet_schema_version (version INTEGER PRIMARY KEY, "
         "applied_at TEXT NOT NULL DEFAULT (strftime('%Y-%m-%dT%H:%M:%fZ', 'now')))");
    for (int v = current_version(db); v < sqlite_fleet_schema_version(); ++v) {
      exec(db, kMigrations[static_cast<std::size_t>(v)]);
      SqliteStatement s(db, "INSERT INTO fleet_schema_version (version) VALUES (?1)");
      s.bind(1, std::to_string(v + 1));
      s.step();
    }
    // The declared figures' columns after the numbered migrations (figure_columns.hpp).
    for (const auto& column : missing_figure_columns(run_columns(db))) {
      exec(db, add_figure_column_sql(column, "REAL"));
    }
  });
}

// Binds a query's text parameters in order.
void bind_all(SqliteStatement& s, const SqlParams& params) {
  for (std::size_t i = 0; i < params.size(); ++i) s.bind(static_cast<int>(i + 1), params[i]);
}

}  // namespace

int sqlite_fleet_schema_version() {
  return static_cast<int>(kMigrations.size());
}

SqliteResultsStore::SqliteResultsStore(const std::filesystem::path& file, Access access) {
  const int flags = access == Access::kReadOnly ? SQLITE_OPEN_READONLY
                                                : SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE;
  if (sqlite3_open_v2(file.c_str(), &db_, flags | SQLITE_OPEN_NOMUTEX, nullptr) != SQLITE_OK) {
    std::string message = db_ ? sqlite3_errmsg(db_) : "out of memory";
    sqlite3_close(db_);
    db_ = nullptr;
    throw std::runtime_error("sqlite results store: cannot open " + file.string() + ": " + message);
  }
  try {
    sqlite3_busy_timeout(db_, 5000);
    if (access == Access::kReadWrite) {
      // As the run index: WAL, so that queries never wait on the run store's writes.
      exec(db_, "PRAGMA journal_mode=WAL; PRAGMA synchronous=FULL; PRAGMA foreign_keys=ON;");
      migrate(db_);
    } else if (current_version(db_) < 1) {
      throw std::runtime_error(
          "sqlite results store: " + file.string() +
          " holds no run summaries yet (wavebenchd fills them at its start and at the end of "
          "every run)");
    }
    const auto missing = missing_figure_columns(run_columns(db_));
    absent_ = ColumnSet(missing.begin(), missing.end());
  } catch (...) {
    sqlite3_close(db_);
    db_ = nullptr;
    throw;
  }
}

SqliteResultsStore::~SqliteResultsStore() {
  sqlite3_close(db_);
}

int SqliteResultsStore::schema_version() {
  return current_version(db_);
}

bool SqliteResultsStore::publish(const RunSummary& run) {
  std::vector<std::optional<std::string>> texts = {
      run.bench,       run.run_id,     run.station, text_or_null(run.operator_name),
      run.unit_serial, run.gear_model, run.spec,    run.spec_version,
      run.procedure,   run.status,     run.reason,  text_or_null(run.verdict)};
  std::string values;
  for (std::size_t i = 1; i <= texts.size() + 8 + fleet_figures().size(); ++i) {
    values += (i > 1 ? ", ?" : "?") + std::to_string(i);
  }
  bool inserted = false;
  transaction(db_, [&] {
    SqliteStatement s(db_, "INSERT OR IGNORE INTO fleet_runs (" + run_insert_columns() +
                               ") VALUES (" + values + ")");
    int i = 1;
    for (const auto& t : texts) s.bind(i++, t);
    s.bind_bool(i++, run.pass);
    s.bind(i++, canonical_utc(run.started_at, "started_at"));
    s.bind(i++, run.finished_at.empty()
                    ? std::nullopt
                    : std::optional<std::string>(canonical_utc(run.finished_at, "finished_at")));
    s.bind(i++, run.software_version);
    s.bind(i++, run.config_hash);
    s.bind(i++, run.samples_ref);
    s.bind(i++, json_text(run.limits));
    s.bind(i++, json_text(run.results));
    for (const auto& figure : fleet_figures()) {
      const auto it = run.figures.find(figure.name);
      s.bind_number(i++, it == run.figures.end() || !std::isfinite(it->second)
                             ? std::nullopt
                             : std::optional<double>(it->second));
    }
    s.step();
    inserted = sqlite3_changes(db_) == 1;
    if (!inserted) return;
    for (const auto& p : run.static_passes) {
      // A repeated (direction, load) in one run keeps its first pass.
      SqliteStatement pass(db_,
                           "INSERT OR IGNORE INTO fleet_static_passes (bench, run_id, direction, "
                           "load_nm, p2p_arcmin, mean_arcmin, std_arcmin) VALUES (?1, ?2, ?3, "
                           "?4, ?5, ?6, ?7)");
      pass.bind(1, run.bench);
      pass.bind(2, run.run_id);
      pass.bind(3, p.direction);
      pass.bind_number(4, p.load_nm);
      const auto finite = [](std::optional<double> v) {
        return v && std::isfinite(*v) ? v : std::nullopt;
      };
      pass.bind_number(5, finite(p.p2p_arcmin));
      pass.bind_number(6, finite(p.mean_arcmin));
      pass.bind_number(7, finite(p.std_arcmin));
      pass.step();
    }
  });
  return inserted;
}

std::vector<FleetRunRow> SqliteResultsStore::runs(const FleetRunQuery& q) {
  const auto query = runs_query(q, kSqliteSql, absent_);
  SqliteStatement s(db_, query.sql);
  bind_all(s, query.params);
  std::vector<FleetRunRow> rows;
  while (s.step()) {
    rows.push_back(
        run_row([&](int col) { return s.text(col); }, [&](int col) { return s.number(col); }));
  }
  return rows;
}

std::vector<TrendPoint> SqliteResultsStore::trend(const FigureQuery& q) {
  const auto query = trend_query(q, checked_figure(q), kSqliteSql, absent_);
  SqliteStatement s(db_, query.sql);
  bind_all(s, query.params);
  std::vector<TrendPoint> points;
  while (s.step()) {
    points.push_back(trend_point(
        static_cast<int>(points.size()), [&](int col) { return s.text(col); },
        [&](int col) { return s.number(col); }));
  }
  return points;
}

SpcAnswer SqliteResultsStore::spc(const FigureQuery& q, const SpecLimits& limits) {
  auto points = trend(q);
  const auto& figure = find_fleet_figure(q.figure);
  std::optional<NewestRunLimit> newest;
  if (*figure.limit_key && !limits.lower && !limits.upper) {
    // As PostgreSQL's `limits ? key`: the key present, whatever its value; a value that is no
    // number gives no limit.
    const std::string path = std::string("$.\"") + figure.limit_key + "\"";
    SqlWhere where(kSqliteSql);
    where.add("gear_model = @", q.gear_model);
    where.add_fixed("status = 'complete'");
    where.add("bench = @", q.bench);
    where.add("json_type(limits, @) IS NOT NULL", path);
    const std::string path_param = where.last_placeholder();
    SqliteStatement s(db_, "SELECT spec, spec_version, CASE WHEN json_type(limits, " + path_param +
                               ") IN ('integer', 'real') THEN json_extract(limits, " + path_param +
                               ") END FROM fleet_runs" + where.sql() +
                               " ORDER BY started_at DESC LIMIT 1");
    bind_all(s, where.params());
    if (s.step()) newest = NewestRunLimit{s.text(0), s.text(1), s.number(2)};
  }
  return spc_answer(std::move(points), figure, limits, newest);
}

}  // namespace wavebench::fleet
