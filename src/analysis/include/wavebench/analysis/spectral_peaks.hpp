#pragma once
// Peak table of an amplitude spectrum with interpolated frequency and amplitude.

#include <vector>

#include "wavebench/analysis/amplitude_spectrum.hpp"
#include "wavebench/analysis/window.hpp"

namespace wavebench::analysis {

struct SpectralPeak {
  double frequency_hz = 0;  // interpolated
  double amplitude = 0;     // interpolated (scalloping corrected for the window)
  int bin = 0;              // the local maximum's bin
  double bin_offset = 0;    // interpolated position relative to `bin`, in bins (-0.5 .. 0.5)
};

struct PeakSearch {
  int max_peaks = 12;
  double min_relative_amplitude = 1e-4;  // of the largest line
  double max_frequency_hz = 0;           // 0 = Nyquist
  double min_frequency_hz = 0;           // lines below are ignored (bin 0 always is)
};

// Local maxima sorted by amplitude, largest first. Interpolation fits a parabola to the
// logarithm of the three bins around the maximum (exact for a Gaussian lobe, within 1 % for
// Hann) and corrects the amplitude with the window's own lobe shape at the fitted offset.
std::vector<SpectralPeak> find_peaks(const AmplitudeSpectrum& spectrum, const PeakSearch& search);

}  // namespace wavebench::analysis
