#include "wavebench/procedures/run_limits.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "quoted_value.hpp"
#include "verdict_table.hpp"
#include "wavebench/metrology/figure_propagation.hpp"

namespace wavebench::procedures {

namespace {

using metrology::LimitDecision;

// FAIL outranks UNDECIDED outranks PASS.
LimitDecision worse(LimitDecision a, LimitDecision b) {
  const auto rank = [](LimitDecision d) {
    return d == LimitDecision::kFail ? 2 : d == LimitDecision::kUndecided ? 1 : 0;
  };
  return rank(a) >= rank(b) ? a : b;
}

std::optional<bool> acceptance(LimitDecision d, UndecidedCounts undecided) {
  if (d == LimitDecision::kPass) return true;
  if (d == LimitDecision::kFail) return false;
  if (undecided == UndecidedCounts::kPass) return true;
  if (undecided == UndecidedCounts::kFail) return false;
  return std::nullopt;
}

}  // namespace

const char* undecided_counts_name(UndecidedCounts counts) {
  switch (counts) {
    case UndecidedCounts::kPass:
      return "pass";
    case UndecidedCounts::kUndecided:
      return "undecided";
    case UndecidedCounts::kFail:
      break;
  }
  return "fail";
}

void validate_limits(const nlohmann::json& limits) {
  if (!limits.is_object()) {
    throw std::invalid_argument("limits: got '" + quoted_value(limits) +
                                "', expected an object of limit names and values");
  }
  for (const auto& [key, value] : limits.items()) {
    bool known = false;
    std::string list;
    for (const auto& f : verdict_figures()) {
      known = known || key == f.limit;
      list += list.empty() ? f.limit : std::string(", ") + f.limit;
    }
    if (!known) {
      throw std::invalid_argument("limits." + quoted_value(key) + ": unknown limit (value '" +
                                  quoted_value(value) + "'), expected one of: " + list);
    }
    if (!value.is_number() || !(value.get<double>() > 0)) {
      throw std::invalid_argument("limits." + key + ": got '" + quoted_value(value) +
                                  "', expected a number > 0");
    }
  }
}

LimitVerdict check_limits(const nlohmann::json& limits, const nlohmann::json& results,
                          UndecidedCounts undecided) {
  LimitVerdict v;
  for (const auto& row : verdict_figures()) {
    if (!limits.contains(row.limit)) continue;
    const double limit = limits.at(row.limit).get<double>();
    for (auto& found : find_figures(results, row.path)) {
      auto figure = row.absolute ? metrology::absolute_of(found.figure) : found.figure;
      if (!std::isfinite(figure.value)) continue;
      const auto decision = row.minimum ? metrology::decide_lower_limit(figure, limit)
                                        : metrology::decide_upper_limit(figure, limit);
      const auto pass = acceptance(decision, undecided);
      v.checks.push_back({{"limit", row.limit},
                          {"name", row.display_name},
                          {"display_unit", row.display_unit},
                          {"value", limit},
                          {"measured", figure.value},
                          {"expanded", figure.expanded()},
                          {"k", figure.coverage_factor},
                          {"uncertainty_stated", found.uncertainty_stated},
                          {"unit", row.unit},
                          {"minimum", row.minimum},
                          {"what", found.where},
                          {"path", found.path},
                          {"decision", metrology::decision_name(decision)},
                          {"pass", pass ? nlohmann::json(*pass) : nlohmann::json()}});
      v.decision = v.decision ? worse(*v.decision, decision) : decision;
    }
  }
  if (v.decision) v.pass = acceptance(*v.decision, undecided);
  return v;
}

}  // namespace wavebench::procedures
