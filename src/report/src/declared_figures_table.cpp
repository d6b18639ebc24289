#include "wavebench/report/declared_figures_table.hpp"

#include <cmath>

#include "wavebench/figures/figure_path.hpp"
#include "wavebench/figures/figure_registry.hpp"

namespace wavebench::report {

namespace {

std::optional<double> expanded_of(const figures::FigureAt& at) {
  const nlohmann::json* holder = at.uncertainty ? at.uncertainty : at.value;
  if (!holder->is_object()) return std::nullopt;
  const auto u = holder->find("expanded");
  if (u == holder->end() || !u->is_number()) return std::nullopt;
  return u->get<double>();
}

}  // namespace

HtmlTable declared_figures_table(const std::string& procedure, const nlohmann::json& results) {
  HtmlTable t{
      "Figures",
      {"figure", "measured at", "value \u00b1 U (k = 2)", "unit", "spec limit", "fleet trend"},
      {}};
  for (const auto* d : figures::figures_of(procedure)) {
    for (const auto& at : figures::find_figure_values(results, d->path)) {
      const auto v = figures::number_of(*at.value);
      if (!v || !std::isfinite(*v)) continue;
      std::string shown = general(*v * d->display_scale, d->display_digits);
      if (const auto u = expanded_of(at); u && std::isfinite(*u) && *u > 0) {
        shown += " \u00b1 " + general(*u * d->display_scale, 2);
      }
      const bool per_element = d->plot == figures::PlotKind::kPerElement;
      t.rows.push_back({{d->label, {}, false},
                        {per_element ? at.where : std::string("\u2013"), {}, false},
                        {shown, {}, false},
                        {d->display_unit, {}, false},
                        {figures::is_limited(*d) ? d->limit.key : "\u2013", {}, false},
                        {figures::is_trended(*d) ? d->fleet.name : "\u2013", {}, false}});
    }
  }
  return t;
}

}  // namespace wavebench::report
