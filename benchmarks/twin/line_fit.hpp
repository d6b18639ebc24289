#pragma once
// Amplitude of known spectral lines by linear least squares on a sine/cosine basis. Unlike an
// FFT bin it separates lines closer than 1/record (89.33 and 90.0 Hz in a 1.75 s record).

#include <span>
#include <vector>

namespace wavebench::bench {

// Amplitudes of `freqs_hz` in (t, x), fitted together with a constant and a linear trend.
std::vector<double> fit_line_amplitudes(std::span<const double> t, std::span<const double> x,
                                        std::span<const double> freqs_hz);

}  // namespace wavebench::bench
