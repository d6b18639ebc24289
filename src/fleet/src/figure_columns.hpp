#pragma once
// The fleet_runs columns the figure declarations ask for, and the migration step that adds
// the ones a store lacks (both stores, on open): a figure declared with a fleet trend gets its
// column without a hand-written migration; columns are never dropped, so an older build still
// reads a newer store, and a newer build reads an older store opened read-only (its absent
// columns read as NULL).

#include <set>
#include <string>
#include <vector>

namespace wavebench::fleet {

using ColumnSet = std::set<std::string>;

// The declared figure columns not in `present`, in declaration order.
std::vector<std::string> missing_figure_columns(const ColumnSet& present);

// "ALTER TABLE fleet_runs ADD COLUMN <column> <type>"; throws std::logic_error for a column
// name that is not [a-z0-9_]+ (it comes from a declaration, never from a request).
std::string add_figure_column_sql(const std::string& column, const std::string& type);

}  // namespace wavebench::fleet
