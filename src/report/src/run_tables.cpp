#include "wavebench/report/run_tables.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "wavebench/model/angle_units.hpp"

namespace wavebench::report {
namespace {

using nlohmann::json;

std::string num(const json& j, const std::string& key, int decimals) {
  const auto v = number(j, key);
  return v ? fixed(*v, decimals) : "\u2013";
}

// The expanded uncertainty of figure `key` of `j` (its `uncertainty` entry), when stated.
std::optional<double> expanded_of(const json& j, const std::string& key) {
  const auto u = j.find("uncertainty");
  if (u == j.end() || !u->is_object()) return std::nullopt;
  const auto f = u->find(key);
  if (f == u->end() || !f->is_object()) return std::nullopt;
  return number(*f, "expanded");
}

// "5.703 ± 0.018": the figure with its expanded uncertainty (k = 2) when results.json states
// one, with as many decimals as U needs for two significant digits (at least `decimals`).
std::string pm(const json& j, const std::string& key, int decimals) {
  const auto v = number(j, key);
  if (!v) return "\u2013";
  const auto u = expanded_of(j, key);
  if (!u) return fixed(*v, decimals);
  if (*u > 0 && std::isfinite(*u)) {
    decimals = std::clamp(1 - static_cast<int>(std::floor(std::log10(*u))), decimals, 9);
  }
  return fixed(*v, decimals) + " \u00b1 " + fixed(*u, decimals);
}

std::string gpm(const json& j, const std::string& key) {
  const auto v = number(j, key);
  if (!v) return "\u2013";
  const auto u = expanded_of(j, key);
  return u ? general(*v) + " \u00b1 " + general(*u, 2) : general(*v);
}

std::string gnum(const json& j, const std::string& key) {
  const auto v = number(j, key);
  return v ? general(*v) : "\u2013";
}

std::string text(const json& j, const std::string& key) {
  const auto it = j.find(key);
  if (it == j.end() || it->is_null()) return "\u2013";
  return it->is_string() ? it->get<std::string>() : it->dump();
}

HtmlTable with_header(bool with_run, std::vector<std::string> header) {
  HtmlTable t;
  if (with_run) header.insert(header.begin(), "run");
  t.header = std::move(header);
  return t;
}

void push(HtmlTable& table, const RunCell& run_cell, std::vector<std::string> cells) {
  std::vector<HtmlCell> row;
  if (run_cell) row.push_back(*run_cell);
  for (auto& c : cells) row.push_back({std::move(c), {}, false});
  table.rows.push_back(std::move(row));
}

void flatten(const json& j, const std::string& prefix, int depth,
             std::vector<std::pair<std::string, std::string>>& out) {
  for (const auto& [key, value] : j.items()) {
    const std::string path = prefix.empty() ? key : prefix + "." + key;
    if (value.is_object() && depth < 3) {
      flatten(value, path, depth + 1, out);
    } else if (value.is_number()) {
      out.emplace_back(path, general(value.get<double>()));
    } else if (value.is_string() || value.is_boolean()) {
      out.emplace_back(path, value.is_string() ? value.get<std::string>() : value.dump());
    }
  }
}

}  // namespace

HtmlCell status_cell(const RunFolder& run) {
  const std::string status = run.field("status", "unknown");
  const std::string reason = run.field("reason");
  HtmlCell cell{status, {}, status != "complete"};
  if (!reason.empty()) cell.text += ": " + reason;
  return cell;
}

HtmlTable runs_table() {
  return with_header(false, {"run", "procedure", "unit serial", "status", "pass", "started (UTC)",
                             "software version"});
}

void add_run_row(HtmlTable& table, const RunFolder& run, const HtmlCell& run_cell) {
  std::string pass = run.field("pass", "\u2013");
  table.rows.push_back({run_cell,
                        {run.field("procedure", "\u2013"), {}, false},
                        {run.field("unit_serial", "\u2013"), {}, false},
                        status_cell(run),
                        {pass, {}, pass == "false"},
                        {run.field("started_at", "\u2013"), {}, false},
                        {run.field("software_version", "\u2013"), {}, false}});
}

HtmlTable static_te_table(bool with_run) {
  auto t = with_header(with_run, {"direction", "load [N*m]", "mean [arcmin]", "p2p [arcmin]",
                                  "std [arcmin]", "points"});
  t.caption = "Static TE per direction and load (value \u00b1 U, k = 2)";
  return t;
}

void add_static_te_rows(HtmlTable& table, const RunFolder& run, const RunCell& run_cell) {
  const json* passes = static_passes(run.results);
  if (!passes) return;
  for (const auto& p : *passes) {
    if (!p.is_object()) continue;
    const auto pts = p.find("points");
    push(table, run_cell,
         {text(p, "direction"), num(p, "load_nm", 1), pm(p, "mean_arcmin", 2),
          pm(p, "p2p_arcmin", 2), pm(p, "std_arcmin", 2),
          pts != p.end() && pts->is_array() ? std::to_string(pts->size()) : "\u2013"});
  }
}

HtmlTable static_lost_motion_table(bool with_run) {
  auto t = with_header(with_run,
                       {"load [N*m]", "mean lost motion [arcmin]", "max lost motion [arcmin]"});
  t.caption = "Lost motion at each position (|reverse - forward|, a width)";
  return t;
}

void add_static_lost_motion_rows(HtmlTable& table, const RunFolder& run, const RunCell& run_cell) {
  const json* profiles = lost_motion_profiles(run.results);
  if (!profiles) return;
  for (const auto& p : *profiles) {
    if (!p.is_object()) continue;
    push(table, run_cell, {num(p, "load_nm", 1), pm(p, "mean_arcmin", 2), pm(p, "max_arcmin", 2)});
  }
}

HtmlTable load_shift_table(bool with_run) {
  auto t = with_header(with_run, {"direction", "load [N*m]", "reference [N*m]", "shift [arcmin]",
                                  "K = T/shift [N*m/rad]", "K [N*m/arcmin]"});
  t.caption = "Shift of mean TE under load";
  return t;
}

void add_load_shift_rows(HtmlTable& table, const RunFolder& run, const RunCell& run_cell) {
  const json* shifts = load_shifts(run.results);
  if (!shifts) return;
  for (const auto& s : *shifts) {
    if (!s.is_object()) continue;
    const auto k = number(s, "stiffness_nm_per_rad");
    push(table, run_cell,
         {text(s, "direction"), num(s, "load_nm", 1), num(s, "reference_load_nm", 1),
          pm(s, "shift_arcmin", 2), k ? gpm(s, "stiffness_nm_per_rad") : "\u2013",
          k ? general(*k / model::kArcminPerRad) : "\u2013"});
  }
}

HtmlTable dynamic_te_table(bool with_run) {
  auto t =
      with_header(with_run, {"mean [arcsec]", "p2p [arcsec]", "RMS [arcsec]", "input speed [rpm]",
                             "output revolutions", "sample rate [Hz]", "named peaks", "aliased"});
  t.caption = "Dynamic TE (value \u00b1 U, k = 2)";
  return t;
}

void add_dynamic_te_rows(HtmlTable& table, const RunFolder& run, const RunCell& run_cell) {
  const json* d = dynamic_section(run.results);
  if (!d) return;
  const auto f_in = number(*d, "input_speed_hz");
  const auto count = [&](const char* key) {
    const auto it = d->find(key);
    return it != d->end() && it->is_array() ? std::to_string(it->size()) : "\u2013";
  };
  push(table, run_cell,
       {pm(*d, "mean_arcsec", 2), pm(*d, "p2p_arcsec", 2), pm(*d, "rms_arcsec", 2),
        f_in ? fixed(*f_in * 60, 1) : "\u2013", num(*d, "output_revolutions", 2),
        num(*d, "sample_rate_hz", 1), count("peaks"), count("aliased")});
}

HtmlTable peaks_table() {
  auto t = with_header(
      false, {"name", "output order", "WG order", "frequency [Hz]", "amplitude [arcsec]"});
  t.caption = "Named peaks";
  return t;
}

void add_peak_rows(HtmlTable& table, const RunFolder& run) {
  const json* d = dynamic_section(run.results);
  if (!d) return;
  for (const auto& p : (*d)["peaks"]) {
    if (!p.is_object()) continue;
    push(table, std::nullopt,
         {text(p, "name"), num(p, "order_output", 2), num(p, "order_input", 3),
          num(p, "frequency_hz", 3), pm(p, "amplitude_arcsec", 3)});
  }
}

HtmlTable aliased_table() {
  auto t = with_header(false, {"name", "predicted [Hz]", "appears at [Hz]",
                               "predicted amplitude [arcsec]", "status"});
  t.caption = "Predicted components above Nyquist (aliased, not found)";
  return t;
}

void add_aliased_rows(HtmlTable& table, const RunFolder& run) {
  const json* d = dynamic_section(run.results);
  if (!d) return;
  const auto it = d->find("aliased");
  if (it == d->end() || !it->is_array()) return;
  for (const auto& a : *it) {
    if (!a.is_object()) continue;
    push(table, std::nullopt,
         {text(a, "name"), num(a, "frequency_hz", 2), num(a, "folded_hz", 2),
          num(a, "amplitude_arcsec", 3), "aliased"});
  }
}

HtmlTable stiffness_table(bool with_run) {
  auto t = with_header(with_run, {"lost motion [arcmin]", "at +/- [N*m]", "backlash [arcmin]",
                                  "hysteresis loss [J]", "K1 [N*m/rad]", "K2 [N*m/rad]",
                                  "K3 [N*m/rad]", "T1 [N*m]", "T2 [N*m]", "fit RMS [arcsec]"});
  t.caption = "Lost motion, hysteresis and stiffness (value \u00b1 U, k = 2)";
  return t;
}

void add_stiffness_rows(HtmlTable& table, const RunFolder& run, const RunCell& run_cell) {
  const json* f = lost_motion_fit(run.results);
  if (!f) return;
  const json& k = (*f)["stiffness"];
  push(table, run_cell,
       {pm(*f, "lost_motion_arcmin", 2), num(*f, "lost_motion_torque_nm", 2),
        pm(*f, "backlash_arcmin", 2), gnum(*f, "hysteresis_loss_j"), gpm(k, "k1_nm_per_rad"),
        gpm(k, "k2_nm_per_rad"), gpm(k, "k3_nm_per_rad"), pm(k, "t1_nm", 2), pm(k, "t2_nm", 2),
        num(k, "rms_residual_arcsec", 2)});
}

HtmlTable limits_table() {
  auto t =
      with_header(false, {"limit", "what", "limit value", "measured \u00b1 U (k = 2)", "decision"});
  t.caption =
      "Limits, guard-banded (ISO 14253-1): PASS when value \u00b1 U lies wholly within the "
      "limit, FAIL when wholly beyond it, UNDECIDED when the limit lies inside the interval";
  return t;
}

void add_limit_rows(HtmlTable& table, const RunFolder& run) {
  const auto it = run.results.find("limit_checks");
  if (it == run.results.end() || !it->is_array()) return;
  for (const auto& c : *it) {
    if (!c.is_object()) continue;
    const auto pass = c.find("pass");
    const bool failed = pass != c.end() && pass->is_boolean() && !pass->get<bool>();
    const bool passed = pass != c.end() && pass->is_boolean() && pass->get<bool>();
    // The decision as ISO 14253-1 gives it; older runs have only `pass`.
    const auto d = c.find("decision");
    std::string decision = d != c.end() && d->is_string() ? d->get<std::string>() : "";
    if (decision.empty()) decision = failed ? "FAIL" : passed ? "PASS" : "\u2013";
    std::string measured = gnum(c, "measured");
    if (const auto u = number(c, "expanded");
        u && !(c.contains("uncertainty_stated") && c["uncertainty_stated"] == false)) {
      measured += " \u00b1 " + general(*u, 2);
    }
    // The verdict table's display name and unit (older runs: the limit key).
    const std::string name = c.contains("name")
                                 ? text(c, "name") + " [" + text(c, "display_unit") + "]"
                                 : text(c, "limit");
    table.rows.push_back({{name, {}, false},
                          {text(c, "what"), {}, false},
                          {gnum(c, "value"), {}, false},
                          {measured, {}, false},
                          {decision, {}, decision != "PASS"}});
  }
}

HtmlTable budget_table(const std::string& group) {
  auto t = with_header(false, {"figure", "source", "type", "standard u", "u_c", "U (k = 2)"});
  t.caption = "Uncertainty budget: " + group +
              " (GUM: standard uncertainties in the figure's unit, sensitivity applied, root sum "
              "of squares; type A statistical, B otherwise)";
  return t;
}

void add_budget_rows(HtmlTable& table, const json& object, const std::string& label) {
  if (!object.is_object()) return;
  const auto u = object.find("uncertainty");
  if (u == object.end() || !u->is_object()) return;
  for (const auto& [key, figure] : u->items()) {
    if (!figure.is_object() || !figure.contains("budget") || !figure["budget"].is_array()) continue;
    const std::string name = label.empty() ? key : label + " " + key;
    bool first = true;
    for (const auto& c : figure["budget"]) {
      push(table, std::nullopt,
           {first ? name + " = " + gnum(figure, "value") : "", text(c, "source"), text(c, "type"),
            gnum(c, "standard"), first ? gnum(figure, "combined_standard") : "",
            first ? gnum(figure, "expanded") : ""});
      first = false;
    }
  }
}

HtmlTable acquisition_table() {
  auto t = with_header(false, {"quantity", "value"});
  t.caption = "Acquisition";
  return t;
}

void add_acquisition_rows(HtmlTable& table, const RunFolder& run) {
  std::vector<std::pair<std::string, std::string>> entries;
  if (const auto it = run.results.find("acquisition"); it != run.results.end() && it->is_object()) {
    flatten(*it, {}, 0, entries);
  }
  if (const auto t = number(run.results, "settle_timeouts")) {
    entries.emplace_back("settle_timeouts", general(*t));
  }
  for (auto& [key, value] : entries) {
    if (value.empty()) continue;  // e.g. no error text
    push(table, std::nullopt, {key, value});
  }
}

HtmlTable twin_table(bool with_run) {
  auto t = with_header(with_run, {"quantity", "value"});
  t.caption = "The twin beside the bench";
  return t;
}

void add_twin_rows(HtmlTable& table, const RunFolder& run, const RunCell& run_cell, bool only_rms) {
  const json* twin = twin_section(run.results);
  if (!twin) return;
  std::vector<std::pair<std::string, std::string>> entries;
  flatten(*twin, {}, 0, entries);
  std::vector<std::string> shown;
  for (auto& [path, value] : entries) {
    if (only_rms) {
      // The compact view: each RMS figure once, however many places the twin reports it.
      if (path.find("rms") == std::string::npos) continue;
      if (std::find(shown.begin(), shown.end(), value) != shown.end()) continue;
      shown.push_back(value);
    }
    push(table, run_cell, {path, value});
  }
}

}  // namespace wavebench::report
