#include "wavebench/fleet/postgres_results_store.hpp"

#include <charconv>
#include <cmath>
#include <stdexcept>

#include "figure_query_rules.hpp"
#include "pg_connection.hpp"
#include "schema_migrations.hpp"
#include "utc_time_text.hpp"
#include "wavebench/fleet/fleet_figures.hpp"

namespace wavebench::fleet {

namespace {

std::optional<std::string> number_text(std::optional<double> value) {
  if (!value || !std::isfinite(*value)) return std::nullopt;
  char buf[32];
  const auto [end, ec] = std::to_chars(buf, buf + sizeof buf, *value);
  return std::string(buf, end);
}

std::optional<std::string> text_or_null(const std::string& text) {
  if (text.empty()) return std::nullopt;
  return text;
}

std::string json_text(const nlohmann::json& value) {
  return value.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

// ISO 8601 UTC with microseconds, as the run index writes them.
std::string iso(const char* column) {
  return std::string("to_char(") + column +
         " AT TIME ZONE 'UTC', 'YYYY-MM-DD\"T\"HH24:MI:SS.US\"Z\"')";
}

// A time bound as the SQLite store reads it (a time without a zone is UTC, not the server's
// TimeZone); a bad one is refused naming its key before it reaches the server.
std::optional<std::string> utc_bound(const std::optional<std::string>& text,
                                     const std::string& key) {
  if (!text) return std::nullopt;
  return canonical_utc(*text, key);
}

// WHERE clauses with their parameters numbered in order.
class Where {
 public:
  void add(const std::string& condition_with_dollar, const std::optional<std::string>& value) {
    if (!value) return;
    params.push_back(*value);
    std::string c = condition_with_dollar;
    c.replace(c.find('$'), 1, "$" + std::to_string(params.size()));
    sql += (sql.empty() ? " WHERE " : " AND ") + c;
  }
  void add_fixed(const std::string& condition) {
    sql += (sql.empty() ? " WHERE " : " AND ") + condition;
  }
  std::string sql;
  PgParams params;
};

}  // namespace

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
  std::string columns =
      "bench, run_id, station, operator, unit_serial, gear_model, spec, spec_version, procedure, "
      "status, reason, verdict, pass, started_at, finished_at, software_version, config_hash, "
      "samples_ref, limits, results";
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
    columns += std::string(", ") + figure.column;
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
    inserted = db_->exec("INSERT INTO fleet_runs (" + columns + ") VALUES (" + values +
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
  Where where;
  where.add("gear_model = $", q.gear_model);
  where.add("bench = $", q.bench);
  where.add("unit_serial = $", q.unit_serial);
  where.add("procedure = $", q.procedure);
  where.add("spec = $", q.spec);
  where.add("verdict = $", q.verdict);
  where.add("status = $", q.status);
  where.add("started_at >= $", utc_bound(q.from, "from"));
  where.add("started_at <= $", utc_bound(q.to, "to"));
  std::string figures;
  for (const auto& f : fleet_figures()) figures += std::string(", ") + f.column;
  const auto r = db_->exec(
      "SELECT bench, run_id, station, COALESCE(operator, ''), unit_serial, gear_model, spec, "
      "spec_version, procedure, status, COALESCE(verdict, ''), " +
          iso("started_at") + ", COALESCE(" + iso("finished_at") +
          ", ''), software_version, samples_ref" + figures + " FROM fleet_runs" + where.sql +
          " ORDER BY started_at DESC, bench, run_id LIMIT " +
          std::to_string(q.limit > 0 ? q.limit : 50),
      where.params);
  std::vector<FleetRunRow> rows;
  for (int i = 0; i < r.rows(); ++i) {
    FleetRunRow row;
    int col = 0;
    // In the SELECT's order.
    for (auto* field :
         {&row.bench, &row.run_id, &row.station, &row.operator_name, &row.unit_serial,
          &row.gear_model, &row.spec, &row.spec_version, &row.procedure, &row.status, &row.verdict,
          &row.started_at, &row.finished_at, &row.software_version, &row.samples_ref}) {
      *field = r.text(i, col++);
    }
    for (const auto& f : fleet_figures()) {
      if (const auto v = r.number(i, col)) row.figures[f.name] = *v;
      ++col;
    }
    rows.push_back(std::move(row));
  }
  return rows;
}

std::vector<TrendPoint> PostgresResultsStore::trend(const FigureQuery& q) {
  const auto& figure = checked_figure(q);
  const bool one_pass = q.direction || q.load_nm;
  Where where;
  where.add("r.gear_model = $", q.gear_model);
  where.add_fixed("r.status = 'complete'");
  where.add("r.bench = $", q.bench);
  where.add("r.started_at >= $", utc_bound(q.from, "from"));
  where.add("r.started_at <= $", utc_bound(q.to, "to"));
  std::string value = std::string("r.") + figure.column;
  std::string from = "fleet_runs r";
  if (one_pass) {
    from += " JOIN fleet_static_passes p ON p.bench = r.bench AND p.run_id = r.run_id";
    value = "p.p2p_arcmin";
    where.add("p.direction = $", q.direction);
    where.add("abs(p.load_nm - $::double precision) < 1e-9", number_text(q.load_nm));
  }
  where.add_fixed(value + " IS NOT NULL");
  // The newest N first (the index on gear_model, started_at), then oldest first for the answer.
  const auto r = db_->exec("SELECT bench, run_id, unit_serial, " + iso("started_at") +
                               ", value FROM (SELECT r.bench, "
                               "r.run_id, r.unit_serial, r.started_at, " +
                               value + " AS value FROM " + from + where.sql +
                               " ORDER BY r.started_at DESC, r.bench DESC, r.run_id DESC" +
                               (q.last > 0 ? " LIMIT " + std::to_string(q.last) : std::string()) +
                               ") newest ORDER BY started_at, bench, run_id",
                           where.params);
  std::vector<TrendPoint> points;
  points.reserve(static_cast<std::size_t>(r.rows()));
  for (int i = 0; i < r.rows(); ++i) {
    points.push_back(
        {i + 1, r.text(i, 3), r.text(i, 0), r.text(i, 1), r.text(i, 2), *r.number(i, 4)});
  }
  return points;
}

SpcAnswer PostgresResultsStore::spc(const FigureQuery& q, const SpecLimits& limits) {
  auto points = trend(q);
  const auto& figure = find_fleet_figure(q.figure);
  std::optional<NewestRunLimit> newest;
  if (*figure.limit_key && !limits.lower && !limits.upper) {
    Where where;
    where.add("gear_model = $", q.gear_model);
    where.add_fixed("status = 'complete'");
    where.add("bench = $", q.bench);
    where.add("limits ? $", std::string(figure.limit_key));
    const auto r =
        db_->exec("SELECT spec, spec_version, (limits->>'" + std::string(figure.limit_key) +
                      "')::double precision FROM "
                      "fleet_runs" +
                      where.sql + " ORDER BY started_at DESC LIMIT 1",
                  where.params);
    if (r.rows() == 1) newest = NewestRunLimit{r.text(0, 0), r.text(0, 1), r.number(0, 2)};
  }
  return spc_answer(std::move(points), figure, limits, newest);
}

}  // namespace wavebench::fleet
