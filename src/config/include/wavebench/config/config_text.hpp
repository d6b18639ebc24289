#pragma once
// The strict YAML checks of drivers/strict_yaml (size, UTF-8, not empty, nesting, duplicate
// keys) for the loaders in src/; their refusals are ConfigError (= strict_yaml::RefusedConfig).

#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <string>

namespace wavebench::config {

// The text of a regular file of at most strict_yaml::kMaxConfigBytes; throws ConfigError.
std::string read_config_text(const std::filesystem::path& path);
// The one document of `text`, checked; throws ConfigError attributed to `source`.
YAML::Node parse_config_yaml(const std::string& text, const std::string& source);

}  // namespace wavebench::config
