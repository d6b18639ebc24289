#include "wavebench/config/config_text.hpp"

#include "wavebench/strict_yaml/strict_yaml.hpp"

namespace wavebench::config {

std::string read_config_text(const std::filesystem::path& path) {
  return strict_yaml::read_config_file(path);
}

YAML::Node parse_config_yaml(const std::string& text, const std::string& source) {
  return strict_yaml::parse_strict_yaml(text, source);
}

}  // namespace wavebench::config
