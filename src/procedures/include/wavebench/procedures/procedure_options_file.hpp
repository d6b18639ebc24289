#pragma once
// Procedure options from YAML (configs/procedures/*.yaml): a mapping of option keys to
// numbers, booleans, strings and lists, as the JSON a RunRequest carries.

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

namespace wavebench::procedures {

// Throws std::invalid_argument naming the file, the key and what is wrong: not a mapping, bad
// YAML, and what drivers/strict_yaml refuses (empty, too large, not UTF-8, duplicate keys).
nlohmann::json procedure_options_from_yaml(const std::string& yaml_text,
                                           const std::string& source = "<string>");
nlohmann::json load_procedure_options(const std::filesystem::path& file);

}  // namespace wavebench::procedures
