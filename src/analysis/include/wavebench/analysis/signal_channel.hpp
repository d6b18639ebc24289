#pragma once
// Picking a channel of a SampledResponse by the name a config uses.

#include <span>
#include <string>
#include <vector>

#include "wavebench/model/simulation.hpp"

namespace wavebench::analysis {

// Throws std::invalid_argument naming the key, the value and the channels expected.
std::span<const double> response_channel(const model::SampledResponse& response,
                                         const std::string& name);
std::vector<std::string> response_channel_names();

double mean_of(std::span<const double> values);
double rms_about_mean(std::span<const double> values);

}  // namespace wavebench::analysis
