#include "wavebench/fleet/fleet_figures.hpp"

#include <stdexcept>
#include <string_view>

#include "wavebench/figures/figure_registry.hpp"

namespace wavebench::fleet {

namespace {

// One trend per fleet name: the first declaration naming it describes it (unit, limit), the
// others only feed it (the torsional procedure's K1 into the lost-motion procedure's trend).
std::vector<FleetFigure> trends() {
  std::vector<FleetFigure> out;
  for (const auto& d : figures::declared_figures()) {
    if (!figures::is_trended(d)) continue;
    bool known = false;
    for (auto& f : out) {
      if (std::string_view(f.name) != d.fleet.name) continue;
      if (std::string_view(f.column) != d.fleet.column) {
        throw std::logic_error(std::string("figure ") + d.name + ": fleet trend " + d.fleet.name +
                               " in column " + d.fleet.column + ", declared before in " + f.column);
      }
      f.paths.push_back(d.path);
      known = true;
    }
    if (known) continue;
    out.push_back({d.fleet.name,
                   d.fleet.column,
                   d.unit,
                   d.limit.key,
                   d.limit.kind == figures::LimitKind::kLower,
                   d.fleet.what,
                   {d.path}});
  }
  return out;
}

}  // namespace

const std::vector<FleetFigure>& fleet_figures() {
  static const std::vector<FleetFigure> figures = trends();
  return figures;
}

const FleetFigure& find_fleet_figure(const std::string& name) {
  std::string names;
  for (const auto& f : fleet_figures()) {
    if (name == f.name) return f;
    names += (names.empty() ? "" : ", ") + std::string(f.name);
  }
  throw std::invalid_argument("figure: got '" + name + "', expected one of " + names);
}

}  // namespace wavebench::fleet
