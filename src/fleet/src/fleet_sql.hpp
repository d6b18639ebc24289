#pragma once
// The fleet stores' queries, written once for both SQL dialects. PostgreSQL and SQLite differ
// here only in how a parameter is numbered ($1 or ?1), how a time column reads back as ISO 8601
// text, and how a text parameter becomes a number; every parameter is bound as text (or null).

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "figure_columns.hpp"
#include "wavebench/fleet/fleet_figures.hpp"
#include "wavebench/fleet/results_store.hpp"

namespace wavebench::fleet {

struct SqlDialect {
  char placeholder;                                    // '$' or '?', followed by the number
  std::string (*iso_time)(const std::string& column);  // the column as canonical_utc() text
  std::string (*as_double)(const std::string& parameter);
};
extern const SqlDialect kPostgresSql;
extern const SqlDialect kSqliteSql;

using SqlParams = std::vector<std::optional<std::string>>;

struct SqlQuery {
  std::string sql;
  SqlParams params;
};

// WHERE clauses with their text parameters numbered in order.
class SqlWhere {
 public:
  explicit SqlWhere(const SqlDialect& dialect) : dialect_(dialect) {}
  // `condition` holds one '@' where the parameter goes; nothing is added without a value.
  void add(const std::string& condition, const std::optional<std::string>& value);
  void add_fixed(const std::string& condition);
  // The placeholder of the last parameter added, to use it again.
  std::string last_placeholder() const;
  const std::string& sql() const { return sql_; }
  SqlParams& params() { return params_; }

 private:
  const SqlDialect& dialect_;
  std::string sql_;
  SqlParams params_;
};

// The shortest text that reads back as the same double; null for none or a non-finite one.
std::optional<std::string> number_text(std::optional<double> value);
// Null for an empty text.
std::optional<std::string> text_or_null(const std::string& text);
std::string json_text(const nlohmann::json& value);
// canonical_utc() of a time bound; throws std::invalid_argument naming `key` (from, to).
std::optional<std::string> utc_bound(const std::optional<std::string>& text,
                                     const std::string& key);

// fleet_runs' columns in publish order, the figure columns after them (fleet_figures()).
std::string run_insert_columns();

// GET /api/fleet/runs: newest first. `absent`: figure columns the store lacks (read as NULL).
SqlQuery runs_query(const FleetRunQuery& query, const SqlDialect& dialect,
                    const ColumnSet& absent = {});
// One row of runs_query()'s answer, from its column readers.
FleetRunRow run_row(const std::function<std::string(int)>& text,
                    const std::function<std::optional<double>(int)>& number);

// The trend of checked_figure(query): columns bench, run_id, unit_serial, started_at, value;
// the newest `last` runs, oldest first.
SqlQuery trend_query(const FigureQuery& query, const FleetFigure& figure, const SqlDialect& dialect,
                     const ColumnSet& absent = {});
// Row `index` (0 the oldest) of trend_query()'s answer.
TrendPoint trend_point(int index, const std::function<std::string(int)>& text,
                       const std::function<std::optional<double>(int)>& number);

}  // namespace wavebench::fleet
