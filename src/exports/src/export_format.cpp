#include "wavebench/exports/export_format.hpp"

namespace wavebench::exports {

std::optional<ExportFormat> export_format_from_name(std::string_view name) {
  if (name == "mat") return ExportFormat::kMat;
  if (name == "hdf5") return ExportFormat::kHdf5;
  if (name == "csv") return ExportFormat::kCsv;
  if (name == "json") return ExportFormat::kJson;
  return std::nullopt;
}

const char* export_format_name(ExportFormat format) {
  switch (format) {
    case ExportFormat::kMat:
      return "mat";
    case ExportFormat::kHdf5:
      return "hdf5";
    case ExportFormat::kCsv:
      return "csv";
    case ExportFormat::kJson:
      return "json";
  }
  return "?";
}

const char* export_format_list() {
  return "mat, hdf5, csv or json";
}

std::string samples_file_name(ExportFormat format) {
  switch (format) {
    case ExportFormat::kMat:
      return "samples.mat";
    case ExportFormat::kHdf5:
      return "samples.h5";
    case ExportFormat::kCsv:
      return "samples.csv";
    case ExportFormat::kJson:
      return "samples.json";
  }
  return "samples";
}

}  // namespace wavebench::exports
