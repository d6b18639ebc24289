#include "wavebench/fleet/run_summary.hpp"

#include <algorithm>
#include <cmath>
#include <string_view>

#include "wavebench/figures/figure_path.hpp"
#include "wavebench/fleet/fleet_figures.hpp"
#include "wavebench/storage/sha256.hpp"

namespace wavebench::fleet {

namespace {

using nlohmann::json;

// Arrays kept in the run folder only: the shared store holds figures, not curves.
bool bulky(const std::string& key) {
  return key == "trace" || key == "points" || key == "order_spectrum" || key == "mean_curve" ||
         key == "revolutions" || key == "residual_before" || key == "residual_after" ||
         key == "fit_curve";
}

json without_bulky(const json& value) {
  if (value.is_object()) {
    json out = json::object();
    for (const auto& [key, item] : value.items()) {
      if (!bulky(key)) out[key] = without_bulky(item);
    }
    return out;
  }
  if (value.is_array()) {
    json out = json::array();
    for (const auto& item : value) out.push_back(without_bulky(item));
    return out;
  }
  return value;
}

// The value at a dotted path, or null.
const json& at(const json& root, std::initializer_list<const char*> path) {
  static const json null_value;
  const json* node = &root;
  for (const char* key : path) {
    if (!node->is_object()) return null_value;
    const auto it = node->find(key);
    if (it == node->end()) return null_value;
    node = &*it;
  }
  return *node;
}

std::string text_or_empty(const json& value) {
  return value.is_string() ? value.get<std::string>() : std::string();
}

// A fleet figure's value in `results`: the first of its paths that the run has; a path over an
// array ([*]) gives the largest magnitude (widths were written negative before #11).
std::optional<double> fleet_value(const json& results, const FleetFigure& figure) {
  for (const char* path : figure.paths) {
    const bool every = std::string_view(path).find("[*]") != std::string_view::npos;
    std::optional<double> best;
    for (const auto& at : figures::find_figure_values(results, path)) {
      const auto v = figures::number_of(*at.value);
      if (!v) continue;
      best = every ? std::max(best.value_or(0.0), std::abs(*v)) : *v;
      if (!every) break;
    }
    if (best) return best;
  }
  return std::nullopt;
}

}  // namespace

std::optional<double> figure_value(const json& value) {
  return figures::number_of(value);
}

RunSummary summarise_run(const storage::RunRecord& run, const json& results_in,
                         const BenchIdentity& identity) {
  const json results = results_in.is_object() ? results_in : json::object();
  RunSummary s;
  s.bench =
      !identity.bench.empty() ? identity.bench : text_or_empty(results.value("bench", json()));
  if (s.bench.empty()) s.bench = "unnamed";
  s.run_id = run.id;
  s.station = identity.station;
  s.operator_name = text_or_empty(at(results, {"operator"}));
  s.unit_serial = run.unit_serial;
  s.procedure = run.procedure;
  s.status = storage::run_status_name(run.status);
  s.reason = run.reason;
  s.verdict = !run.verdict.empty() ? run.verdict
              : run.pass           ? std::string(*run.pass ? "PASS" : "FAIL")
                                   : std::string();
  s.pass = run.pass;
  s.started_at = run.started_at;
  s.finished_at = run.finished_at;
  s.software_version = run.software_version;
  s.config_hash = run.config_hash;
  s.samples_ref = s.bench + ":" + run.id + "/samples.wbs";
  s.spec = run.spec;
  const json& spec = at(results, {"spec"});
  if (spec.is_object()) {
    s.gear_model = text_or_empty(spec.value("model", json()));
    s.spec_version = storage::sha256_hex(spec.dump()).substr(0, 16);
  }
  const json limits = json::parse(run.limits_json, nullptr, false);
  if (limits.is_object()) s.limits = limits;

  const json& passes = at(results, {"static"});
  if (passes.is_array()) {
    for (const auto& p : passes) {
      if (!p.is_object() || !p.contains("direction") || !p.contains("load_nm")) continue;
      const auto load = figure_value(p["load_nm"]);
      if (!load) continue;
      s.static_passes.push_back({text_or_empty(p["direction"]), *load,
                                 figure_value(p.value("p2p_arcmin", json())),
                                 figure_value(p.value("mean_arcmin", json())),
                                 figure_value(p.value("std_arcmin", json()))});
    }
  }
  for (const auto& figure : fleet_figures()) {
    if (const auto v = fleet_value(results, figure)) s.figures[figure.name] = *v;
  }
  s.results = without_bulky(results);
  return s;
}

}  // namespace wavebench::fleet
