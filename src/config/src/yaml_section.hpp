#pragma once
// The twin case's reading on top of the one config reader (strict_yaml::YamlSection): the
// bounds that keep a twin run finite and the sinusoid, which only twin cases write.

#include <cstddef>
#include <limits>
#include <string>

#include "wavebench/config/units.hpp"
#include "wavebench/model/gear_params.hpp"
#include "wavebench/strict_yaml/yaml_section.hpp"

namespace wavebench::config {

using strict_yaml::kMaxListItems;
using strict_yaml::YamlSection;

// Physical bounds that keep a run finite: no gear turns its input faster (about 95 000 rpm),
// no excitation order or tooth count is larger, no sinusoid in a case is faster.
inline constexpr double kMaxSpeedRadS = 1e4;
inline constexpr double kMaxOrder = 1e4;
inline constexpr double kMaxSinusoidHz = 1e5;

// Integer keys of a twin case hold an int (counts, seeds, signs).
inline constexpr long long kIntMin = std::numeric_limits<int>::min();
inline constexpr long long kIntMax = std::numeric_limits<int>::max();

// A sinusoid at `key` of `s`: a plain quantity (the offset) or {offset, amplitude, frequency,
// phase}; absent = all zero.
model::Sinusoid sinusoid_or(YamlSection& s, const std::string& key, Dimension dimension);

// The mapping at the top of a twin-case document (refusals attributed by the caller).
YamlSection document_section(const YAML::Node& root);

}  // namespace wavebench::config
