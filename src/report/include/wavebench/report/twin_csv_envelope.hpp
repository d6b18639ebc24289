#pragma once
// twin.csv (the twin beside the bench: t, index, measured_te_arcsec, predicted_te_arcsec,
// residual_arcsec) read line by line into the rows its plot draws: every row while the file
// holds no more than 2 × columns, else the min/max envelope per column of the time range
// (analysis::MinMaxEnvelope), so the memory does not grow with the run. The time range is that
// of the first and the last usable row (the file is written in time order; rows outside it are
// left out and noted). When the file has no residual column it is measured - predicted.

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "wavebench/report/run_folder.hpp"

namespace wavebench::report {

// nullopt (and a note) when the file is empty or has no usable row; a missing file is nullopt
// without a note. Malformed rows (a cell count unlike the header's, a value that is not a
// number) are skipped and counted in a note.
std::optional<TwinTrace> read_twin_csv_envelope(const std::filesystem::path& path,
                                                std::size_t columns,
                                                std::vector<std::string>& notes);

}  // namespace wavebench::report
