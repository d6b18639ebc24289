#pragma once
// The result tables of a run, from results.json and status.json, shared by a run's report
// (one run, no run column) and the session index (a first column naming the run). Each
// add_*_rows appends nothing when the run lacks that section.

#include <optional>

#include "wavebench/report/html_page.hpp"
#include "wavebench/report/run_folder.hpp"

namespace wavebench::report {

using RunCell = std::optional<HtmlCell>;  // the first column when the table gathers runs

HtmlTable runs_table();
void add_run_row(HtmlTable& table, const RunFolder& run, const HtmlCell& run_cell);

HtmlTable static_te_table(bool with_run);  // direction, load, mean/p2p/std arcmin
void add_static_te_rows(HtmlTable& table, const RunFolder& run, const RunCell& run_cell);

HtmlTable static_lost_motion_table(bool with_run);  // |reverse − forward| per load
void add_static_lost_motion_rows(HtmlTable& table, const RunFolder& run, const RunCell& run_cell);

HtmlTable load_shift_table(bool with_run);  // mean TE shift under load and implied K
void add_load_shift_rows(HtmlTable& table, const RunFolder& run, const RunCell& run_cell);

HtmlTable dynamic_te_table(bool with_run);  // mean/p2p/RMS arcsec, speed, peaks
void add_dynamic_te_rows(HtmlTable& table, const RunFolder& run, const RunCell& run_cell);

HtmlTable peaks_table();  // order, Hz, amplitude arcsec, name
void add_peak_rows(HtmlTable& table, const RunFolder& run);
HtmlTable aliased_table();  // predicted above Nyquist, marked aliased
void add_aliased_rows(HtmlTable& table, const RunFolder& run);

HtmlTable stiffness_table(bool with_run);  // lost motion, backlash, hysteresis, K1–K3, T1/T2
void add_stiffness_rows(HtmlTable& table, const RunFolder& run, const RunCell& run_cell);

HtmlTable twin_table(bool with_run);  // every number of results.json "twin", by path
// `only_rms`: just the RMS figures (the session's compact view).
void add_twin_rows(HtmlTable& table, const RunFolder& run, const RunCell& run_cell, bool only_rms);

// results.json "limit_checks": limit, what, value, measured ± U, decision (PASS, FAIL,
// UNDECIDED)
HtmlTable limits_table();
void add_limit_rows(HtmlTable& table, const RunFolder& run);

// One figure group's uncertainty budgets: a row per contribution of every figure in the
// `uncertainty` object of `object` (label + figure name, source, type, u, u_c, U).
HtmlTable budget_table(const std::string& group);
void add_budget_rows(HtmlTable& table, const nlohmann::json& object, const std::string& label);

// Every number of results.json "acquisition" (samples, gaps, bus load, ...), and
// "settle_timeouts" of a static run.
HtmlTable acquisition_table();
void add_acquisition_rows(HtmlTable& table, const RunFolder& run);

// The status as shown: "aborted: <reason>" etc.; alert when not complete.
HtmlCell status_cell(const RunFolder& run);

}  // namespace wavebench::report
