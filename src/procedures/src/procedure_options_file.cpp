#include "wavebench/procedures/procedure_options_file.hpp"

#include <yaml-cpp/yaml.h>

#include <stdexcept>

#include "wavebench/strict_yaml/strict_yaml.hpp"
#include "wavebench/strict_yaml/yaml_section.hpp"

namespace wavebench::procedures {

namespace {

nlohmann::json scalar(const YAML::Node& n) {
  const std::string text = n.Scalar();
  if (n.Tag() == "!") return text;  // quoted: a string
  if (text == "true" || text == "false") return text == "true";
  try {
    std::size_t used = 0;
    const long long i = std::stoll(text, &used);
    if (used == text.size()) return i;
  } catch (const std::exception&) {
  }
  try {
    std::size_t used = 0;
    const double d = std::stod(text, &used);
    if (used == text.size()) return d;
  } catch (const std::exception&) {
  }
  return text;
}

nlohmann::json to_json(const YAML::Node& n) {
  switch (n.Type()) {
    case YAML::NodeType::Map: {
      nlohmann::json j = nlohmann::json::object();
      for (const auto& kv : n) j[kv.first.as<std::string>()] = to_json(kv.second);
      return j;
    }
    case YAML::NodeType::Sequence: {
      nlohmann::json j = nlohmann::json::array();
      for (const auto& item : n) j.push_back(to_json(item));
      return j;
    }
    case YAML::NodeType::Scalar:
      return scalar(n);
    default:
      return nullptr;
  }
}

}  // namespace

nlohmann::json procedure_options_from_yaml(const std::string& yaml_text,
                                           const std::string& source) {
  try {
    const YAML::Node root = strict_yaml::parse_strict_yaml(yaml_text, source);
    // The options are checked by their procedure, against its own schema; here only the shape.
    strict_yaml::document_section(root, source, "a mapping of procedure options");
    return to_json(root);
  } catch (const strict_yaml::RefusedConfig& e) {
    throw std::invalid_argument(e.what());
  }
}

nlohmann::json load_procedure_options(const std::filesystem::path& file) {
  std::string text;
  try {
    text = strict_yaml::read_config_file(file);
  } catch (const strict_yaml::RefusedConfig& e) {
    throw std::invalid_argument(e.what());
  }
  return procedure_options_from_yaml(text, file.string());
}

}  // namespace wavebench::procedures
