#include "wavebench/fleet/postgres_results_store.hpp"

#include <stdexcept>

#include "figure_query_rules.hpp"
#include "fleet_sql.hpp"
#include "pg_connection.hpp"
#include "schema_migrations.hpp"
#include "wavebench/fleet/fleet_figures.hpp"
#include "wavebench/fleet/utc_time_text.hpp"

namespace wavebench::fleet {

int fleet_schema_version() {
  return fleet_schema_migrations();
}

PostgresResultsStore::PostgresResultsStore(const ResultsConfig& config) {
  if (!config.shared()) {
    throw std::invalid_argument(
        "results.store: got 'sqlite', expected postgresql for a shared "
        "results store");
  }
  check_conninfo(config.url);
  const std::string password =
      config.password_file.empty() ? std::string() : read_password_file(config.password_file);
  db_ = std::make_unique<PgConnection>(config.url, password);
  migrate_fleet_schema(*db_);
}

PostgresResultsStore::~PostgresResultsStore() = default;

bool PostgresResultsStore::connected() const {
  return db_ && db_->ok();
}

int PostgresResultsStore::schema_version() {
  return std::stoi(db_->exec("SELECT COALESCE(MAX(version), 0) FROM schema_version").text(0, 0));
}

bool PostgresResultsStore::publish(const RunSummary& run) {
  PgParams params = {
      run.bench,
      run.run_id,
      run.station,
      text_or_null(run.operator_name),
      run.unit_serial,
      run.gear_model,
      run.spec,
      run.spec_version,
      run.procedure,
      run.status,
      run.reason,
      text_or_null(run.verdict),
      run.pass ? std::optional<std::string>(*run.pass ? "true" : "false") : std::nullopt,
      run.started_at,
      text_or_null(run.finished_at),
      run.software_version,
      run.config_hash,
      run.samples_ref,
      json_text(run.limits),
      json_text(run.results)};
  for (const auto& figure : fleet_figures()) {
    const auto it = run.figures.find(figure.name);
    params.push_back(
        number_text(it == run.figures.end() ? std::nullopt : std::optional<double>(it->second)));
  }
  std::string values;
  for (std::size_t i = 1; i <= params.size(); ++i) {
    values += (i > 1 ? ", $" : "$") + std::to_string(i);
  }
  bool inserted = false;
  db_->transaction([&] {
    inserted = db_->exec("INSERT INTO fleet_runs (" + run_insert_columns() + ") VALUES (" + values +
                             ") ON CONFLICT (bench, run_id) DO NOTHING",
                         params)
                   .affected() == 1;
    if (!inserted) return;
    for (const auto& p : run.static_passes) {
      // A repeated (direction, load) in one run keeps its first pass.
      db_->exec(
          "INSERT INTO fleet_static_passes (bench, run_id, direction, load_nm, p2p_arcmin, "
          "mean_arcmin, std_arcmin) VALUES ($1, $2, $3, $4, $5, $6, $7) ON CONFLICT DO NOTHING",
          {run.bench, run.run_id, p.direction, number_text(p.load_nm), number_text(p.p2p_arcmin),
           number_text(p.mean_arcmin), number_text(p.std_arcmin)});
    }
  });
  return inserted;
}

std::vector<FleetRunRow> PostgresResultsStore::runs(const FleetRunQuery& q) {
  const auto query = runs_query(q, kPostgresSql);
  const auto r = db_->exec(query.sql, query.params);
  std::vector<FleetRunRow> rows;
  rows.reserve(static_cast<std::size_t>(r.rows()));
  for (int i = 0; i < r.rows(); ++i) {
    rows.push_back(run_row([&](int col) { return r.text(i, col); },
                           [&](int col) { return r.number(i, col); }));
  }
  return rows;
}

std::vector<TrendPoint> PostgresResultsStore::trend(const FigureQuery& q) {
  const auto query = trend_query(q, checked_figure(q), kPostgresSql);
  const auto r = db_->exec(query.sql, query.params);
  std::vector<TrendPoint> points;
  points.reserve(static_cast<std::size_t>(r.rows()));
  for (int i = 0; i < r.rows(); ++i) {
    points.push_back(trend_point(
        i, [&](int col) { return r.text(i, col); }, [&](int col) { return r.number(i, col); }));
  }
  return points;
}

SpcAnswer PostgresResultsStore::spc(const FigureQuery& q, const SpecLimits& limits) {
  auto points = trend(q);
  const auto& figure = find_fleet_figure(q.figure);
  std::optional<NewestRunLimit> newest;
  if (*figure.limit_key && !limits.lower && !limits.upper) {
    SqlWhere where(kPostgresSql);
    where.add("gear_model = @", q.gear_model);
    where.add_fixed("status = 'complete'");
    where.add("bench = @", q.bench);
    where.add("limits ? @", std::string(figure.limit_key));
    const auto r =
        db_->exec("SELECT spec, spec_version, (limits->>'" + std::string(figure.limit_key) +
                      "')::double precision FROM "
                      "fleet_runs" +
                      where.sql() + " ORDER BY started_at DESC LIMIT 1",
                  where.params());
    if (r.rows() == 1) newest = NewestRunLimit{r.text(0, 0), r.text(0, 1), r.number(0, 2)};
  }
  return spc_answer(std::move(points), figure, limits, newest);
}

}  // namespace wavebench::fleet
