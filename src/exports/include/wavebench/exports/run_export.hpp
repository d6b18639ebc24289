#pragma once
// A run's whole export into a folder (`wavebench export`): samples.<format>, run.json and
// results.json, each written under a temporary name and renamed only when all of them are
// written and synced. The folder ends complete or as it was: a first export that fails removes
// the folder it created. A run that is still running is refused unless a partial export is
// asked for; then every file says it is partial (docs/formats/exports.md).

#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "wavebench/exports/sample_export.hpp"

namespace wavebench::exports {

// The run's record says it is still running (its samples are still being written).
bool run_still_running(const nlohmann::json& run);

// Why the run may not be exported now (it is running and `allow_partial` is false), or nothing.
// `flag` is how the caller names the permission ("--partial", "partial=1").
std::optional<std::string> running_run_refusal(const nlohmann::json& run, bool allow_partial,
                                               const std::string& flag);

// Throws std::runtime_error naming the folder or file and what failed (a refusal included).
ExportSummary export_run(ExportInput input, ExportFormat format, const std::filesystem::path& dir,
                         bool allow_partial);

}  // namespace wavebench::exports
