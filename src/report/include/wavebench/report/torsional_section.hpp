#pragma once
// The locked-output torsional test in a report (results.json "torsional"): its figures, each as
// value ± U (k = 2); the uncertainty budget behind them; the loop as the catalogues draw it,
// torque on the x axis and torsion angle (twist) on the y axis.

#include <nlohmann/json.hpp>
#include <optional>

#include "wavebench/report/figure.hpp"
#include "wavebench/report/run_tables.hpp"

namespace wavebench::report {

// "torsional": {...}, nullptr when absent.
const nlohmann::json* torsional_section(const nlohmann::json& results);

// Hysteresis loss, lost motion, backlash, K1–K3, T1/T2 with U; T_max and slipped points.
HtmlTable torsional_table(bool with_run);
void add_torsional_rows(HtmlTable& table, const RunFolder& run, const RunCell& run_cell);

// One row per contribution of each figure: figure, source, GUM type, standard uncertainty.
HtmlTable torsional_budget_table();
void add_torsional_budget_rows(HtmlTable& table, const RunFolder& run);

// The points per branch (voided ones marked), the mean curve and the fitted three-segment
// curve; nullopt without points.
std::optional<Figure> torsional_loop_figure(const nlohmann::json& torsional);

}  // namespace wavebench::report
