#pragma once
// Twin against measured (bench.md §5): the overlay rows, the residual (measured − predicted TE:
// RMS, p2p, spectrum, via procedures::twin_residual) and twin.csv in a run folder.

#include <cstdint>
#include <filesystem>
#include <span>
#include <vector>

#include "wavebench/analysis/amplitude_spectrum.hpp"
#include "wavebench/procedures/twin_calibration.hpp"
#include "wavebench/twin/twin_point.hpp"

namespace wavebench::twin {

// The samples with both a measured and a predicted TE.
struct TwinOverlay {
  std::vector<std::uint64_t> index;
  std::vector<double> t_s;
  std::vector<double> measured_te_rad;
  std::vector<double> predicted_te_rad;
};

TwinOverlay twin_overlay(std::span<const TwinPoint> points);

// Throws std::invalid_argument when fewer than 8 samples overlap.
procedures::TwinResidual twin_overlay_residual(const TwinOverlay& overlay,
                                               analysis::SpectrumAnalyser& analyser,
                                               analysis::Window window = analysis::Window::kHann);

// t,index,measured_te_arcsec,predicted_te_arcsec,residual_arcsec; one row per point, an empty
// field where a value is missing. Written atomically (storage::write_file_atomically).
void write_twin_csv(const std::filesystem::path& file, std::span<const TwinPoint> points);

}  // namespace wavebench::twin
