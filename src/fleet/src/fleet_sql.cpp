#include "fleet_sql.hpp"

#include <charconv>
#include <cmath>

#include "wavebench/fleet/utc_time_text.hpp"
#include "wavebench/storage/like_prefix.hpp"

namespace wavebench::fleet {

namespace {

std::string pg_iso_time(const std::string& column) {
  // ISO 8601 UTC with microseconds, as canonical_utc() writes them.
  return "to_char(" + column + " AT TIME ZONE 'UTC', 'YYYY-MM-DD\"T\"HH24:MI:SS.US\"Z\"')";
}
std::string pg_as_double(const std::string& parameter) {
  return parameter + "::double precision";
}
// The SQLite store keeps times as canonical_utc() text already.
std::string sqlite_iso_time(const std::string& column) {
  return column;
}
std::string sqlite_as_double(const std::string& parameter) {
  return "CAST(" + parameter + " AS REAL)";
}

}  // namespace

const SqlDialect kPostgresSql{'$', pg_iso_time, pg_as_double};
const SqlDialect kSqliteSql{'?', sqlite_iso_time, sqlite_as_double};

void SqlWhere::add(const std::string& condition, const std::optional<std::string>& value) {
  if (!value) return;
  params_.push_back(*value);
  std::string c = condition;
  c.replace(c.find('@'), 1, last_placeholder());
  add_fixed(c);
}

void SqlWhere::add_fixed(const std::string& condition) {
  sql_ += (sql_.empty() ? " WHERE " : " AND ") + condition;
}

std::string SqlWhere::last_placeholder() const {
  return dialect_.placeholder + std::to_string(params_.size());
}

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

std::optional<std::string> utc_bound(const std::optional<std::string>& text,
                                     const std::string& key) {
  if (!text) return std::nullopt;
  return canonical_utc(*text, key);
}

std::string run_insert_columns() {
  std::string columns =
      "bench, run_id, station, operator, unit_serial, gear_model, spec, spec_version, procedure, "
      "status, reason, verdict, pass, started_at, finished_at, software_version, config_hash, "
      "samples_ref, limits, results";
  for (const auto& figure : fleet_figures()) columns += std::string(", ") + figure.column;
  return columns;
}

SqlQuery runs_query(const FleetRunQuery& q, const SqlDialect& dialect, const ColumnSet& absent) {
  SqlWhere where(dialect);
  where.add("gear_model = @", q.gear_model);
  where.add("bench = @", q.bench);
  where.add("unit_serial = @", q.unit_serial);
  if (q.unit_serial_prefix) {
    // UPPER on both sides: PostgreSQL's LIKE minds case, SQLite's does not (for ASCII).
    where.add(std::string("UPPER(unit_serial) LIKE UPPER(@)") + storage::kLikeEscapeClause,
              storage::like_prefix_pattern(*q.unit_serial_prefix));
  }
  where.add("procedure = @", q.procedure);
  where.add("spec = @", q.spec);
  where.add("verdict = @", q.verdict);
  where.add("status = @", q.status);
  where.add("started_at >= @", utc_bound(q.from, "from"));
  where.add("started_at <= @", utc_bound(q.to, "to"));
  std::string figures;
  for (const auto& f : fleet_figures()) {
    figures += absent.contains(f.column) ? std::string(", NULL") : std::string(", ") + f.column;
  }
  return {
      "SELECT bench, run_id, station, COALESCE(operator, ''), unit_serial, gear_model, spec, "
      "spec_version, procedure, status, COALESCE(verdict, ''), " +
          dialect.iso_time("started_at") + ", COALESCE(" + dialect.iso_time("finished_at") +
          ", ''), software_version, samples_ref" + figures + " FROM fleet_runs" + where.sql() +
          " ORDER BY started_at DESC, bench, run_id LIMIT " +
          std::to_string(q.limit > 0 ? q.limit : 50),
      std::move(where.params())};
}

FleetRunRow run_row(const std::function<std::string(int)>& text,
                    const std::function<std::optional<double>(int)>& number) {
  FleetRunRow row;
  int col = 0;
  // In runs_query()'s SELECT order.
  for (auto* field :
       {&row.bench, &row.run_id, &row.station, &row.operator_name, &row.unit_serial,
        &row.gear_model, &row.spec, &row.spec_version, &row.procedure, &row.status, &row.verdict,
        &row.started_at, &row.finished_at, &row.software_version, &row.samples_ref}) {
    *field = text(col++);
  }
  for (const auto& f : fleet_figures()) {
    if (const auto v = number(col)) row.figures[f.name] = *v;
    ++col;
  }
  return row;
}

SqlQuery trend_query(const FigureQuery& q, const FleetFigure& figure, const SqlDialect& dialect,
                     const ColumnSet& absent) {
  const bool one_pass = q.direction || q.load_nm;
  SqlWhere where(dialect);
  where.add("r.gear_model = @", q.gear_model);
  where.add_fixed("r.status = 'complete'");
  where.add("r.bench = @", q.bench);
  where.add("r.started_at >= @", utc_bound(q.from, "from"));
  where.add("r.started_at <= @", utc_bound(q.to, "to"));
  std::string value =
      absent.contains(figure.column) ? std::string("NULL") : std::string("r.") + figure.column;
  std::string from = "fleet_runs r";
  if (one_pass) {
    from += " JOIN fleet_static_passes p ON p.bench = r.bench AND p.run_id = r.run_id";
    value = "p.p2p_arcmin";
    where.add("p.direction = @", q.direction);
    where.add("abs(p.load_nm - " + dialect.as_double("@") + ") < 1e-9", number_text(q.load_nm));
  }
  where.add_fixed(value + " IS NOT NULL");
  // The newest N first (the index on gear_model, started_at), then oldest first for the answer.
  return {"SELECT bench, run_id, unit_serial, " + dialect.iso_time("started_at") +
              ", value FROM (SELECT r.bench, r.run_id, r.unit_serial, r.started_at, " + value +
              " AS value FROM " + from + where.sql() +
              " ORDER BY r.started_at DESC, r.bench DESC, r.run_id DESC" +
              (q.last > 0 ? " LIMIT " + std::to_string(q.last) : std::string()) +
              ") newest ORDER BY started_at, bench, run_id",
          std::move(where.params())};
}

TrendPoint trend_point(int index, const std::function<std::string(int)>& text,
                       const std::function<std::optional<double>(int)>& number) {
  return {index + 1, text(3), text(0), text(1), text(2), number(4).value_or(NAN)};
}

}  // namespace wavebench::fleet
