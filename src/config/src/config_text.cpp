#include "wavebench/config/config_text.hpp"

#include "wavebench/config/config_error.hpp"
#include "wavebench/strict_yaml/strict_yaml.hpp"

namespace wavebench::config {
namespace {

ConfigError as_config_error(const strict_yaml::RefusedConfig& e) {
  return ConfigError(e.key(), e.value(), e.expected(), e.source());
}

}  // namespace

std::string read_config_text(const std::filesystem::path& path) {
  try {
    return strict_yaml::read_config_file(path);
  } catch (const strict_yaml::RefusedConfig& e) {
    throw as_config_error(e);
  }
}

YAML::Node parse_config_yaml(const std::string& text, const std::string& source) {
  try {
    return strict_yaml::parse_strict_yaml(text, source);
  } catch (const strict_yaml::RefusedConfig& e) {
    throw as_config_error(e);
  }
}

}  // namespace wavebench::config
