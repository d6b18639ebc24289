#pragma once
// The figures the shared store keeps in typed columns (trend and SPC read them): the name a
// user types, the column of fleet_runs, its unit, and the run-limit key of the product spec
// that bounds it (docs/formats/fleet-store.md). Generated from the figures declared beside
// their procedures (wavebench/figures): a declaration with a fleet trend is a column here, and
// the stores add a missing column when they open (their migrations).

#include <optional>
#include <string>
#include <vector>

namespace wavebench::fleet {

struct FleetFigure {
  const char* name;       // "static_te_p2p"
  const char* column;     // "static_p2p_arcmin" (a column of fleet_runs)
  const char* unit;       // "arcmin"
  const char* limit_key;  // run_limits key of its spec limit; "" when none
  bool limit_is_minimum;  // the limit is a lower one (min_k1)
  const char* what;
  // Where results.json holds it, in declaration order: the first that a run has gives the
  // value; a path with [*] gives its largest magnitude.
  std::vector<const char*> paths;
};

const std::vector<FleetFigure>& fleet_figures();
// Throws std::invalid_argument naming `figure`, the value and the names expected.
const FleetFigure& find_fleet_figure(const std::string& name);

}  // namespace wavebench::fleet
