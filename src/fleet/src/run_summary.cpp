#include "wavebench/fleet/run_summary.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "wavebench/storage/sha256.hpp"

namespace wavebench::fleet {

namespace {

using nlohmann::json;

// Arrays kept in the run folder only: the shared store holds figures, not curves.
bool bulky(const std::string& key) {
  return key == "trace" || key == "points" || key == "order_spectrum" || key == "mean_curve" ||
         key == "revolutions" || key == "residual_before" || key == "residual_after";
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

void put(std::map<std::string, double>& figures, const char* name, std::optional<double> value) {
  if (value) figures[name] = *value;
}

std::optional<double> first_of(std::optional<double> a, std::optional<double> b) {
  return a ? a : b;
}

std::optional<double> largest(const json& list, const char* key) {
  std::optional<double> best;
  if (!list.is_array()) return best;
  for (const auto& item : list) {
    if (!item.is_object() || !item.contains(key)) continue;
    if (const auto v = figure_value(item[key])) {
      best = std::max(best.value_or(0.0), std::abs(*v));  // widths written negative before #11
    }
  }
  return best;
}

}  // namespace

std::optional<double> figure_value(const json& value) {
  if (value.is_number()) return value.get<double>();
  if (value.is_object() && value.contains("value") && value["value"].is_number()) {
    return value["value"].get<double>();
  }
  return std::nullopt;
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
  auto& f = s.figures;
  put(f, "static_te_p2p", largest(passes, "p2p_arcmin"));
  put(f, "static_lost_motion", largest(at(results, {"lost_motion"}), "max_abs_arcmin"));
  put(f, "lost_motion",
      first_of(figure_value(at(results, {"lost_motion_fit", "lost_motion_arcmin"})),
               figure_value(at(results, {"torsional", "lost_motion_arcmin"}))));
  for (const auto& [name, key] :
       {std::pair{"k1", "k1_nm_per_rad"}, std::pair{"k2", "k2_nm_per_rad"},
        std::pair{"k3", "k3_nm_per_rad"}}) {
    put(f, name,
        first_of(figure_value(at(results, {"lost_motion_fit", "stiffness", key})),
                 figure_value(at(results, {"torsional", "stiffness", key}))));
  }
  put(f, "dynamic_te_p2p", figure_value(at(results, {"dynamic", "p2p_arcsec"})));
  put(f, "dynamic_te_rms", figure_value(at(results, {"dynamic", "rms_arcsec"})));
  put(f, "twin_residual_before",
      figure_value(at(results, {"twin", "calibration", "rms_before_arcsec"})));
  put(f, "twin_residual_after",
      figure_value(at(results, {"twin", "calibration", "rms_after_arcsec"})));
  s.results = without_bulky(results);
  return s;
}

}  // namespace wavebench::fleet
