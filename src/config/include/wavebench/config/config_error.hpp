#pragma once
// A config that cannot be used: the one refusal type of every loader (strict_yaml), named here
// for the loaders in src/. The message names the key path, the offending value and what was
// expected, so a user can fix the file without reading the code.

#include "wavebench/strict_yaml/strict_yaml.hpp"

namespace wavebench::config {

using ConfigError = strict_yaml::RefusedConfig;

}  // namespace wavebench::config
