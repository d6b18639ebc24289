#include "wavebench/metrology/uncertainty_budget.hpp"

#include <cmath>
#include <numeric>
#include <stdexcept>

namespace wavebench::metrology {

UncertainFigure& UncertainFigure::add(std::string source, double standard, char evaluation,
                                      bool varies_between_repeats) {
  budget.push_back({std::move(source), evaluation, std::abs(standard), varies_between_repeats});
  return *this;
}

double UncertainFigure::combined_standard() const {
  double sum = 0;
  for (const auto& c : budget) sum += c.standard * c.standard;
  return std::sqrt(sum);
}

double UncertainFigure::expanded() const {
  return coverage_factor * combined_standard();
}

double quantisation_standard(double step) {
  return std::abs(step) / std::sqrt(12.0);
}

double rectangular_standard(double half_width) {
  return std::abs(half_width) / std::sqrt(3.0);
}

double standard_of_mean(double sample_std, int n) {
  return n < 2 ? 0.0 : sample_std / std::sqrt(static_cast<double>(n));
}

double sample_std(const std::vector<double>& values) {
  const auto n = values.size();
  if (n < 2) return 0.0;
  const double mean = std::accumulate(values.begin(), values.end(), 0.0) / static_cast<double>(n);
  double ss = 0;
  for (double v : values) ss += (v - mean) * (v - mean);
  return std::sqrt(ss / static_cast<double>(n - 1));
}

nlohmann::json to_json(const UncertainFigure& figure, double scale) {
  nlohmann::json budget = nlohmann::json::array();
  for (const auto& c : figure.budget) {
    budget.push_back({{"source", c.source},
                      {"type", std::string(1, c.evaluation)},
                      {"standard", c.standard * scale},
                      {"varies_between_repeats", c.varies_between_repeats}});
  }
  return {{"value", figure.value * scale},
          {"expanded", figure.expanded() * scale},
          {"k", figure.coverage_factor},
          {"combined_standard", figure.combined_standard() * scale},
          {"budget", budget}};
}

bool is_uncertain_figure_json(const nlohmann::json& j) {
  return j.is_object() && j.contains("value") && j["value"].is_number() && j.contains("expanded") &&
         j["expanded"].is_number() && j.contains("budget") && j["budget"].is_array();
}

UncertainFigure uncertain_figure_from_json(const nlohmann::json& j, double scale) {
  if (!is_uncertain_figure_json(j)) {
    throw std::invalid_argument("uncertain figure: got '" + j.dump().substr(0, 80) +
                                "', expected an object with value, expanded and budget");
  }
  UncertainFigure f;
  f.value = j["value"].get<double>() / scale;
  if (const auto k = j.find("k"); k != j.end() && k->is_number())
    f.coverage_factor = k->get<double>();
  for (const auto& c : j["budget"]) {
    if (!c.is_object()) continue;
    const std::string type = c.value("type", std::string("B"));
    f.add(c.value("source", std::string()), c.value("standard", 0.0) / scale,
          type.empty() ? 'B' : type[0], c.value("varies_between_repeats", false));
  }
  return f;
}

const char* decision_name(LimitDecision decision) {
  switch (decision) {
    case LimitDecision::kPass:
      return "PASS";
    case LimitDecision::kFail:
      return "FAIL";
    case LimitDecision::kUndecided:
      break;
  }
  return "UNDECIDED";
}

LimitDecision decide_upper_limit(const UncertainFigure& figure, double max) {
  const double u = figure.expanded();
  if (figure.value + u <= max) return LimitDecision::kPass;
  if (figure.value - u > max) return LimitDecision::kFail;
  return LimitDecision::kUndecided;
}

LimitDecision decide_lower_limit(const UncertainFigure& figure, double min) {
  const double u = figure.expanded();
  if (figure.value - u >= min) return LimitDecision::kPass;
  if (figure.value + u < min) return LimitDecision::kFail;
  return LimitDecision::kUndecided;
}

}  // namespace wavebench::metrology
