#pragma once
// Matching spectral peaks to the TE terms that cause them (model.md §9, seeds 000-002 Table 3).

#include <string>
#include <vector>

#include "wavebench/analysis/linearised_gear.hpp"
#include "wavebench/analysis/spectral_peaks.hpp"
#include "wavebench/model/gear_params.hpp"

namespace wavebench::analysis {

struct PeakSource {
  std::string source;              // TeTerm::source
  double term_frequency_hz = 0;    // the term's own frequency at the run's mean speed
  double predicted_amplitude = 0;  // |H(f) A_j| in the analysed signal's unit
  double share = 0;                // |c_j| / sum |c_k| over the peak's terms; sums to 1
  double in_phase_share = 0;       // Re(c_j conj(S)) / |S|^2, S the complex sum; sums to 1
  bool aliased = false;            // term lies above Nyquist and folds onto this line
};

struct AttributedPeak {
  double frequency_hz = 0;
  double amplitude = 0;
  double tolerance_hz = 0;          // how far a term's (folded) frequency may lie from the line
  double predicted_amplitude = 0;   // |sum c_j| (complex sum at one frequency)
  std::vector<PeakSource> sources;  // ranked by share, largest first
  bool aliased = false;             // any of the sources is folded
  std::string label;                // "te", "unattributed" or "nonlinear: a+b" / "nonlinear: 2a"
};

struct AttributionInput {
  std::vector<model::TeTerm> terms;
  model::GearGeometry geometry;
  double mean_input_speed = 0;  // [rad/s]
  double sample_rate_hz = 0;
  double resolution_hz = 0;  // fs / N of the spectrum
  Window window = Window::kHann;
  LinearGearCoefficients linear;  // transfer function TE -> signal
  std::string signal;             // channel analysed
  // false: no transfer function for the signal (or no linear model); shares then follow the
  // bare TE amplitudes.
  bool use_transfer = true;
};

// Frequency a term appears at after sampling at fs (folded into 0 .. fs/2).
double folded_frequency_hz(double frequency_hz, double sample_rate_hz);

// Half-width (Hz) within which a term's frequency counts as the peak's: the window's main lobe
// half-width in bins (Hann 2, flat-top 5, rectangular 1) times the resolution, but at least
// 1.5 bins.
double bin_tolerance_hz(Window window, double resolution_hz);

std::vector<AttributedPeak> attribute_peaks(const std::vector<SpectralPeak>& peaks,
                                            const AttributionInput& input);

}  // namespace wavebench::analysis
