#pragma once
// The formats `wavebench export --format` writes a run's samples in, and their file names.

#include <optional>
#include <string>
#include <string_view>

namespace wavebench::exports {

enum class ExportFormat { kMat, kHdf5, kCsv, kJson };

// "mat", "hdf5", "csv", "json"; nullopt for anything else.
std::optional<ExportFormat> export_format_from_name(std::string_view name);
const char* export_format_name(ExportFormat format);
// "mat, hdf5, csv or json": what a refusal says was expected.
const char* export_format_list();
// samples.mat, samples.h5, samples.csv, samples.json
std::string samples_file_name(ExportFormat format);

}  // namespace wavebench::exports
