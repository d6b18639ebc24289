#include "repeat_combination.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "wavebench/metrology/uncertainty_budget.hpp"

namespace wavebench::procedures {

namespace {

using metrology::UncertainFigure;

// The same place in every repeat, or null where a repeat has no such place.
std::vector<const nlohmann::json*> same_place(const std::vector<const nlohmann::json*>& nodes,
                                              const std::string& key) {
  std::vector<const nlohmann::json*> out;
  for (const auto* n : nodes) {
    const nlohmann::json* found = nullptr;
    if (n && n->is_object()) {
      if (const auto it = n->find(key); it != n->end()) found = &*it;
    }
    out.push_back(found);
  }
  return out;
}

std::vector<const nlohmann::json*> same_index(const std::vector<const nlohmann::json*>& nodes,
                                              std::size_t i) {
  std::vector<const nlohmann::json*> out;
  for (const auto* n : nodes)
    out.push_back(n && n->is_array() && i < n->size() ? &(*n)[i] : nullptr);
  return out;
}

nlohmann::json combine_figure(const std::vector<const nlohmann::json*>& nodes) {
  std::vector<UncertainFigure> figures;
  for (const auto* n : nodes) {
    if (n && metrology::is_uncertain_figure_json(*n)) {
      figures.push_back(metrology::uncertain_figure_from_json(*n));
    }
  }
  if (figures.size() < 2) return *nodes.front();
  const double r = static_cast<double>(figures.size());
  UncertainFigure out;
  out.coverage_factor = figures.front().coverage_factor;
  std::vector<double> values;
  for (const auto& f : figures) {
    out.value += f.value / r;
    values.push_back(f.value);
  }
  double removed_squares = 0;  // mean over the repeats of Σ u² of the removed contributions
  for (const auto& c : figures.front().budget) {
    double squares = 0;
    for (const auto& f : figures) {
      for (const auto& d : f.budget) {
        if (d.source == c.source) squares += d.standard * d.standard;
      }
    }
    if (c.varies_between_repeats) {
      removed_squares += squares / r;
    } else {
      out.add(c.source, std::sqrt(squares / r), c.evaluation, false);
    }
  }
  const double spread = metrology::standard_of_mean(metrology::sample_std(values),
                                                     static_cast<int>(figures.size()));
  out.add(kRepeatSpreadSource, std::max(spread, std::sqrt(removed_squares / r)), 'A', true);
  return metrology::to_json(out);
}

nlohmann::json combine(const std::vector<const nlohmann::json*>& nodes) {
  const nlohmann::json& first = *nodes.front();
  if (metrology::is_uncertain_figure_json(first)) return combine_figure(nodes);
  if (first.is_array()) {
    nlohmann::json out = nlohmann::json::array();
    for (std::size_t i = 0; i < first.size(); ++i) out.push_back(combine(same_index(nodes, i)));
    return out;
  }
  if (!first.is_object()) return first;
  nlohmann::json out = nlohmann::json::object();
  for (const auto& [key, value] : first.items()) out[key] = combine(same_place(nodes, key));
  // The plain figures beside an `uncertainty` object follow their combined figures.
  if (const auto u = out.find("uncertainty"); u != out.end() && u->is_object()) {
    for (const auto& [key, figure] : u->items()) {
      if (out.contains(key) && out[key].is_number() &&
          metrology::is_uncertain_figure_json(figure)) {
        out[key] = figure["value"];
      } else if (out.contains(key) && out[key].is_array() && figure.is_array() &&
                 out[key].size() == figure.size()) {
        for (std::size_t i = 0; i < figure.size(); ++i) {
          if (out[key][i].is_number() && metrology::is_uncertain_figure_json(figure[i])) {
            out[key][i] = figure[i]["value"];
          }
        }
      }
    }
  }
  return out;
}

}  // namespace

nlohmann::json combine_repeats(const std::vector<nlohmann::json>& repeats) {
  if (repeats.empty()) {
    throw std::invalid_argument("combine_repeats: no repeat; expected at least one");
  }
  if (repeats.size() == 1) return repeats.front();
  std::vector<const nlohmann::json*> nodes;
  for (const auto& r : repeats) nodes.push_back(&r);
  return combine(nodes);
}

}  // namespace wavebench::procedures
