#pragma once
// The procedures a run may name, as the API serves them (GET /api/procedures): name, title,
// description and options schema, from the same declarations that parse the options.

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace wavebench::procedures {

// {"procedures": [{"name", "title", "description", "options": [OptionSpec::to_json(), ...],
//                  "figures": [figures::to_json(declaration), ...]}]}
nlohmann::json procedures_json();

// "static", "dynamic", "lost-motion", in the registry's order.
std::vector<std::string> procedure_names();

}  // namespace wavebench::procedures
