#pragma once
// The endurance run in a report (results.json "endurance"): the trend of every output
// revolution (TE mean, p2p and RMS, the mesh lines, the brake temperature) as a plot and a
// table, with the twin's residual per revolution (results.json twin.diagnosis.revolutions)
// beside it: a residual that grows while the TE trend stays put is an early sign of wear.

#include <nlohmann/json.hpp>
#include <optional>

#include "wavebench/report/figure.hpp"
#include "wavebench/report/html_page.hpp"

namespace wavebench::report {

// "endurance": {...}, nullptr when absent.
const nlohmann::json* endurance_section(const nlohmann::json& results);

// One row per revolution: revolution, end time, mean, p2p, RMS, mesh lines, brake temperature.
HtmlTable endurance_trend_table(const nlohmann::json& endurance);

// TE figures, mesh lines, brake temperature and the twin's residual against the revolution;
// nullopt without revolutions. `twin_diagnosis` may be null.
std::optional<Figure> endurance_trend_figure(const nlohmann::json& endurance,
                                             const nlohmann::json* twin_diagnosis);

}  // namespace wavebench::report
