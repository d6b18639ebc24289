#include "figure_query_rules.hpp"

#include <stdexcept>

namespace wavebench::fleet {

const FleetFigure& checked_figure(const FigureQuery& q) {
  const auto& figure = find_fleet_figure(q.figure);
  if ((q.direction || q.load_nm) && std::string(figure.name) != "static_te_p2p") {
    throw std::invalid_argument("direction/load: given for figure '" + q.figure +
                                "', expected them only with static_te_p2p");
  }
  if (q.gear_model.empty()) {
    throw std::invalid_argument("gear_model: got '', expected the gear model to trend");
  }
  return figure;
}

SpcAnswer spc_answer(std::vector<TrendPoint> points, const FleetFigure& figure,
                     const SpecLimits& given, const std::optional<NewestRunLimit>& newest) {
  SpcAnswer answer;
  answer.points = std::move(points);
  if (given.lower || given.upper) {
    answer.limits = given;
    answer.limits_from = "command line";
  } else if (newest && newest->value) {
    (figure.limit_is_minimum ? answer.limits.lower : answer.limits.upper) = newest->value;
    answer.limits_from = newest->spec.empty()
                             ? std::string("the newest run's limits")
                             : "spec " + newest->spec + " (" + newest->spec_version + ")";
  } else {
    answer.limits_from = "none";
  }
  if (answer.points.size() >= 2) {
    std::vector<double> values;
    values.reserve(answer.points.size());
    for (const auto& p : answer.points) values.push_back(p.value);
    answer.figures = spc_figures(values, answer.limits);
  }
  return answer;
}

}  // namespace wavebench::fleet
