#include "schema_migrations.hpp"

#include <array>
#include <cstddef>
#include <string>

#include "figure_columns.hpp"

namespace wavebench::fleet {

namespace {

// Never edit a migration once released: add the next one.
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
  pass BOOLEAN,
  started_at TIMESTAMPTZ NOT NULL,
  finished_at TIMESTAMPTZ,
  software_version TEXT NOT NULL,
  config_hash TEXT NOT NULL,
  samples_ref TEXT NOT NULL,
  static_p2p_arcmin DOUBLE PRECISION,
  static_lost_motion_arcmin DOUBLE PRECISION,
  lost_motion_arcmin DOUBLE PRECISION,
  k1_nm_per_rad DOUBLE PRECISION,
  k2_nm_per_rad DOUBLE PRECISION,
  k3_nm_per_rad DOUBLE PRECISION,
  dynamic_p2p_arcsec DOUBLE PRECISION,
  dynamic_rms_arcsec DOUBLE PRECISION,
  twin_residual_before_arcsec DOUBLE PRECISION,
  twin_residual_after_arcsec DOUBLE PRECISION,
  limits JSONB NOT NULL DEFAULT '{}',
  results JSONB NOT NULL DEFAULT '{}',
  published_at TIMESTAMPTZ NOT NULL DEFAULT now(),
  PRIMARY KEY (bench, run_id)
);
CREATE INDEX fleet_runs_by_model ON fleet_runs (gear_model, started_at);
CREATE INDEX fleet_runs_by_started ON fleet_runs (started_at);
CREATE INDEX fleet_runs_by_unit ON fleet_runs (unit_serial, started_at);
CREATE TABLE fleet_static_passes (
  bench TEXT NOT NULL,
  run_id TEXT NOT NULL,
  direction TEXT NOT NULL,
  load_nm DOUBLE PRECISION NOT NULL,
  p2p_arcmin DOUBLE PRECISION,
  mean_arcmin DOUBLE PRECISION,
  std_arcmin DOUBLE PRECISION,
  PRIMARY KEY (bench, run_id, direction, load_nm),
  FOREIGN KEY (bench, run_id) REFERENCES fleet_runs (bench, run_id) ON DELETE CASCADE
);
)sql"};

// pg_advisory_xact_lock key: "wavebench" in ASCII, the schema's own lock.
constexpr const char* kLock = "SELECT pg_advisory_xact_lock(7809639758601545074)";

int current_version(PgConnection& db) {
  db.exec(
      "CREATE TABLE IF NOT EXISTS schema_version (version INTEGER PRIMARY KEY, "
      "applied_at TIMESTAMPTZ NOT NULL DEFAULT now())");
  const auto r = db.exec("SELECT COALESCE(MAX(version), 0) FROM schema_version");
  return std::stoi(r.text(0, 0));
}

ColumnSet run_columns(PgConnection& db) {
  const auto r = db.exec(
      "SELECT column_name FROM information_schema.columns WHERE table_name = 'fleet_runs' AND "
      "table_schema = current_schema()");
  ColumnSet present;
  for (int i = 0; i < r.rows(); ++i) present.insert(r.text(i, 0));
  return present;
}

// The declared figures' columns the table lacks (figure_columns.hpp), under the schema's lock.
// A step computed from the declarations, not numbered: schema_version stays the numbered one.
void add_figure_columns(PgConnection& db) {
  if (missing_figure_columns(run_columns(db)).empty()) return;
  db.transaction([&] {
    db.exec(kLock);
    for (const auto& column : missing_figure_columns(run_columns(db))) {
      db.exec(add_figure_column_sql(column, "DOUBLE PRECISION"));
    }
  });
}

}  // namespace

int fleet_schema_migrations() {
  return static_cast<int>(kMigrations.size());
}

int migrate_fleet_schema(PgConnection& db) {
  int version = 0;
  for (;;) {
    bool applied = false;
    db.transaction([&] {
      db.exec(kLock);
      version = current_version(db);
      if (version >= fleet_schema_migrations()) return;
      db.exec_script(kMigrations[static_cast<std::size_t>(version)]);
      ++version;
      db.exec("INSERT INTO schema_version (version) VALUES ($1)", {std::to_string(version)});
      applied = true;
    });
    if (!applied) break;
  }
  add_figure_columns(db);
  return version;
}

}  // namespace wavebench::fleet
