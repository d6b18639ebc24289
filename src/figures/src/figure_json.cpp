#include "wavebench/figures/figure_registry.hpp"

namespace wavebench::figures {

namespace {

const char* limit_kind_name(LimitKind k) {
  switch (k) {
    case LimitKind::kUpper:
      return "upper";
    case LimitKind::kLower:
      return "lower";
    case LimitKind::kUpperOfMagnitude:
      return "upper_of_magnitude";
    case LimitKind::kNone:
      break;
  }
  return "none";
}

const char* plot_kind_name(PlotKind k) {
  return k == PlotKind::kPerElement ? "per_element" : "value";
}

}  // namespace

nlohmann::json to_json(const FigureDeclaration& f) {
  return {{"name", f.name},
          {"procedure", f.procedure},
          {"path", f.path},
          {"uncertainty_path", f.uncertainty_path},
          {"label", f.label},
          {"unit", f.unit},
          {"display_unit", f.display_unit},
          {"display_scale", f.display_scale},
          {"display_digits", f.display_digits},
          {"limit", is_limited(f) ? nlohmann::json{{"kind", limit_kind_name(f.limit.kind)},
                                                   {"key", f.limit.key}}
                                  : nlohmann::json()},
          {"fleet", is_trended(f) ? nlohmann::json{{"name", f.fleet.name},
                                                   {"column", f.fleet.column},
                                                   {"what", f.fleet.what}}
                                  : nlohmann::json()},
          {"plot", plot_kind_name(f.plot)}};
}

nlohmann::json figures_json(std::string_view procedure) {
  nlohmann::json list = nlohmann::json::array();
  for (const auto* f : figures_of(procedure)) list.push_back(to_json(*f));
  return list;
}

nlohmann::json all_figures_json() {
  nlohmann::json list = nlohmann::json::array();
  for (const auto& f : declared_figures()) list.push_back(to_json(f));
  return list;
}

}  // namespace wavebench::figures
