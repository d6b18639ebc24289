#include "verdict_table.hpp"

#include "wavebench/figures/figure_path.hpp"
#include "wavebench/figures/figure_registry.hpp"

namespace wavebench::procedures {

namespace {

// The declared figures a spec may bound, as the verdict reads them.
std::vector<VerdictFigure> limited_figures() {
  std::vector<VerdictFigure> out;
  for (const auto& f : figures::declared_figures()) {
    if (!figures::is_limited(f)) continue;
    out.push_back({f.name, f.limit.key, f.dimension, f.unit, f.per_unit, f.path,
                   f.limit.kind == figures::LimitKind::kLower,
                   f.limit.kind == figures::LimitKind::kUpperOfMagnitude, f.label, f.display_unit});
  }
  return out;
}

}  // namespace

std::span<const VerdictFigure> verdict_figures() {
  static const std::vector<VerdictFigure> table = limited_figures();
  return table;
}

std::vector<FoundFigure> find_figures(const nlohmann::json& results, const std::string& path) {
  std::vector<FoundFigure> out;
  for (const auto& at : figures::find_figure_values(results, path)) {
    FoundFigure f;
    f.path = at.path;
    f.where = at.where;
    if (at.uncertainty && metrology::is_uncertain_figure_json(*at.uncertainty)) {
      f.figure = metrology::uncertain_figure_from_json(*at.uncertainty);
      f.uncertainty_stated = true;
    } else if (metrology::is_uncertain_figure_json(*at.value)) {
      f.figure = metrology::uncertain_figure_from_json(*at.value);
      f.uncertainty_stated = true;
    } else if (at.value->is_number()) {
      f.figure.value = at.value->get<double>();
    } else {
      continue;  // another shape: nothing to judge
    }
    out.push_back(std::move(f));
  }
  return out;
}

}  // namespace wavebench::procedures
