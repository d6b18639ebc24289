#pragma once
// What every ResultsStore does the same around its own SQL: the checks of a figure query, and
// the SPC answer from the trend and the limits found (so PostgreSQL and SQLite agree).

#include <optional>
#include <string>
#include <vector>

#include "wavebench/fleet/fleet_figures.hpp"
#include "wavebench/fleet/results_store.hpp"

namespace wavebench::fleet {

// The query's figure. Throws std::invalid_argument for an unknown figure, a direction or load
// with another figure than static_te_p2p, or no gear model.
const FleetFigure& checked_figure(const FigureQuery& query);

// The spec limit of the newest complete run that names the figure's limit key.
struct NewestRunLimit {
  std::string spec, spec_version;
  std::optional<double> value;
};

// `given` (the command line's) wins over the newest run's limit; SPC over 2 points or more.
SpcAnswer spc_answer(std::vector<TrendPoint> points, const FleetFigure& figure,
                     const SpecLimits& given, const std::optional<NewestRunLimit>& newest);

}  // namespace wavebench::fleet
