#pragma once
// The report's figure table, generated from the figures the run's procedure declares
// (src/figures): one row per figure found in results.json (per array element for a figure
// over passes), value ± U (k = 2) in its display unit, its spec-limit key and fleet trend.

#include <nlohmann/json.hpp>
#include <string>

#include "wavebench/report/html_page.hpp"

namespace wavebench::report {

HtmlTable declared_figures_table(const std::string& procedure, const nlohmann::json& results);

}  // namespace wavebench::report
