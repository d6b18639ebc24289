#pragma once
// Finding a declared figure in results.json: every place its path reaches.

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

namespace wavebench::figures {

struct FigureAt {
  std::string path;                       // the concrete path: "static[1].p2p_arcmin"
  std::string where;                      // "static[1] reverse 60 N·m": what the array element is
  const nlohmann::json* value = nullptr;  // the figure: a number or a figure object
  const nlohmann::json* uncertainty = nullptr;  // beside it (its object's `uncertainty`), or null
};

// Every place `path` reaches in `results` (none when a key on the way is missing). A null
// value (not computed) is left out.
std::vector<FigureAt> find_figure_values(const nlohmann::json& results, const std::string& path);

// The number of a figure: a number, or an uncertain figure object's `value`; null otherwise.
std::optional<double> number_of(const nlohmann::json& value);

}  // namespace wavebench::figures
