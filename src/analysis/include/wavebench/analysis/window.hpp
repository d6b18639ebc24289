#pragma once
// Spectral windows and their coherent gain, so a windowed sine reads its true amplitude.

#include <cstddef>
#include <vector>

#include "wavebench/analysis/analysis_options.hpp"

namespace wavebench::analysis {

// Periodic (DFT-even) coefficients: the window's period is n, so the spectrum of a sine on a
// bin has the textbook main-lobe shape.
std::vector<double> window_coefficients(Window window, std::size_t n);
// Coefficient i of the n above, without the table.
double window_coefficient(Window window, std::size_t i, std::size_t n);

// Sum of the coefficients divided by n: the factor a sine's line is scaled by.
double coherent_gain(Window window);

const char* window_name(Window window);

// The window's normalised amplitude response at `offset_bins` from a line (1 at 0), in the
// long-record limit: what a line off the bin grid reads, relative to its true amplitude.
double window_lobe(Window window, double offset_bins);

}  // namespace wavebench::analysis
