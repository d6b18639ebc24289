#pragma once
// The sampled response of a twin run as CSV: one row per sample, SI columns, and the angles
// also in arcsec (the unit TE is read in).

#include <filesystem>
#include <ostream>
#include <string>
#include <vector>

#include "wavebench/model/simulation.hpp"

namespace wavebench::report {

// Column names in the order written.
std::vector<std::string> timeseries_columns();

void write_timeseries_csv(std::ostream& out, const model::SampledResponse& response);
// Throws std::runtime_error when the file cannot be written.
void write_timeseries_csv(const std::filesystem::path& path,
                          const model::SampledResponse& response);

}  // namespace wavebench::report
