#pragma once
// What a verdict judges (issue #11): each product spec key, the limit key a request's "limits"
// uses for it, its unit, and where results.json holds the figure; generated from the figures
// declared beside their procedures (src/figures, issue #23): a declared figure with a spec
// limit is judged; nothing here changes for a new one.
//
// A path is keys separated by dots; `name[*]` takes every element of an array (one check per
// element). The figure at the end of a path is found, first match wins:
//   1. beside it, in its object's `uncertainty` object under the same key (static, dynamic,
//      lost-motion: "static[*].p2p_arcmin" reads static[i].uncertainty.p2p_arcmin);
//   2. the key itself, when it holds an UncertainFigure object (to_json: value, expanded, ...);
//   3. the key itself as a plain number: a figure with no stated uncertainty (U = 0).

#include <nlohmann/json.hpp>
#include <span>
#include <string>
#include <vector>

#include "wavebench/metrology/uncertainty_budget.hpp"
#include "wavebench/strict_yaml/units.hpp"

namespace wavebench::procedures {

struct VerdictFigure {
  const char* spec_key;  // configs/specs/*.yaml ("static_te_p2p")
  const char* limit;     // run_limits key ("static_p2p_arcmin")
  strict_yaml::Dimension dimension;
  const char* unit;  // of the limit key and of the figure in results.json
  double per_unit;   // SI per `unit`
  const char* path;  // in results.json
  bool minimum;      // a lower limit (stiffness); otherwise an upper one
  bool absolute;     // judged on the figure's magnitude (a mean TE of either sign)
  // What a certificate, the run page and the report call the figure and its unit: written
  // here once and carried into results.json's limit_checks ("name", "display_unit").
  const char* display_name;  // "Static TE, peak-to-peak"
  const char* display_unit;  // "arcmin", "N·m/rad"
};

std::span<const VerdictFigure> verdict_figures();

struct FoundFigure {
  std::string where;  // "static[1] reverse 60 N·m"
  std::string path;   // the concrete path: "static[1].p2p_arcmin"
  metrology::UncertainFigure figure;
  bool uncertainty_stated = false;  // false: a plain number, U = 0
};

// Every figure `path` reaches in `results` (none when a key on the way is missing).
std::vector<FoundFigure> find_figures(const nlohmann::json& results, const std::string& path);

}  // namespace wavebench::procedures
