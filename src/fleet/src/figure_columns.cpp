#include "figure_columns.hpp"

#include <stdexcept>

#include "wavebench/fleet/fleet_figures.hpp"

namespace wavebench::fleet {

std::vector<std::string> missing_figure_columns(const ColumnSet& present) {
  std::vector<std::string> out;
  for (const auto& f : fleet_figures()) {
    if (!present.contains(f.column)) out.emplace_back(f.column);
  }
  return out;
}

std::string add_figure_column_sql(const std::string& column, const std::string& type) {
  const bool plain =
      !column.empty() && column.size() <= 63 &&
      column.find_first_not_of("abcdefghijklmnopqrstuvwxyz0123456789_") == std::string::npos;
  if (!plain) {
    throw std::logic_error("fleet column: got '" + column +
                           "', expected [a-z0-9_]+ of at most 63 characters");
  }
  return "ALTER TABLE fleet_runs ADD COLUMN " + column + " " + type;
}

}  // namespace wavebench::fleet
