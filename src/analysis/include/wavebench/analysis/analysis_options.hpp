#pragma once
// What the analysis of a twin run computes (model.md §9). Filled from a twin case's
// `analysis:` section by the config loader; SI units.

#include <optional>
#include <string>
#include <vector>

namespace wavebench::analysis {

enum class Window { kHann, kFlatTop, kRectangular };

struct SpectrumOptions {
  std::string signal = "alpha2";  // channel of SampledResponse: alpha2, omega2, te, twist, ...
  Window window = Window::kHann;
  double max_frequency_hz = 0;  // 0 = Nyquist
  int max_peaks = 12;
  double min_relative_amplitude = 1e-4;  // peaks below this fraction of the largest are dropped
};

struct PoincareOptions {
  std::string excitation_source;  // TE term whose period strobes the section; "" = largest
  int max_clusters = 16;          // above this the motion is quasi-periodic or chaotic
};

struct SweepOptions {  // up/down speed sweep (seed 001: 100 -> 2700 rpm)
  bool enabled = false;
  double from_speed = 0;  // input speed [rad/s]
  double to_speed = 0;    // [rad/s]
  int steps = 0;
  double settle_time = 0;       // [s] per speed before recording
  double record_time = 0;       // [s] per speed
  double jump_threshold = 0.3;  // relative amplitude change between neighbours = a jump
};

struct SensitivityOptions {  // d(vibration)/d(tolerance) per TE source; Monte Carlo
  bool enabled = false;
  double relative_step = 0.1;
  int monte_carlo_runs = 0;
  unsigned seed = 1;
};

struct AnalysisOptions {
  SpectrumOptions spectrum;
  bool order_spectrum = true;
  PoincareOptions poincare;
  SweepOptions sweep;
  SensitivityOptions sensitivity;
  bool linearise = true;
};

}  // namespace wavebench::analysis
