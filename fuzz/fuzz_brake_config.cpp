// The brake-map loader on arbitrary text, as load_brake_config_file reads a file: the strict
// text checks, then the `brake:` section or the whole document. RefusedConfig and
// BrakeConfigError are the documented refusals; anything else is a finding.
#include <cstddef>
#include <cstdint>
#include <string>

#include "wavebench/modbus/brake_config.hpp"
#include "wavebench/strict_yaml/strict_yaml.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const YAML::Node root = wavebench::strict_yaml::parse_strict_yaml(text, "fuzz.yaml");
    (void)wavebench::modbus::load_brake_config(root.IsMap() && root["brake"] ? root["brake"]
                                                                             : root);
  } catch (const wavebench::strict_yaml::RefusedConfig&) {  // BrakeConfigError is one
  }
  return 0;
}
