#pragma once
// The twin as a diagnostic (issue #11, item 5): the residual (measured − predicted TE) is cut
// into whole output revolutions of the input angle (θ1 from its start to start ± 2πN), and
// each revolution's residual and prediction are resampled on θ1 and transformed over exactly
// that revolution (rectangular window: every line of an integer output order falls on its bin).
// A line of the residual above its expected band is flagged with the order it sits on and the
// error sources the twin's own TE terms put at that order, ranked (analysis::attribute_peaks).
//
// The expected band at output order k, per revolution (bench.md §5 has no band; this is ours):
//   band_k = max(floor_factor · σ, noise_factor · median_k |R_k|, relative_band · |P_k|)
//   σ         the sensor floor: the configured output-encoder noise (without one, the
//             residual's noise measured in that revolution by third differences,
//             estimate_te_noise_floor_arcsec, which a tooth pulse's edges inflate); a line
//             smaller than the sensors' own noise RMS is not a finding however clean its bin;
//   median    the median line of the revolution's residual spectrum (white noise spreads
//             evenly; noise_factor 8 puts a noise bin above it with probability e^-44);
//   |P_k|     the twin's own predicted line: a nominal twin knows its unit's TE terms only to
//             their tolerance (the simulated unit differs from its nominal twin by 8 % in
//             amplitude and 4° in phase: 11 % of the line), so relative_band is 0.25 for a
//             nominal twin; a twin calibrated to the unit can be given less.
// Not the first revolution's residual: a unit may arrive with its defect, and then the first
// revolution is not healthy. Order 0 (the residual's mean) is never flagged: the twin's
// offset and stiffness are calibration matters.
//
// Lines above their band in one revolution are grouped by harmonic series: a line whose order
// is a multiple (up to max_harmonic) of a lower flagged line's joins its series; the lowest
// order of a series is the flag's order (a local tooth error is a pulse train: its lines sit
// at every multiple of its mesh order, the fundamental largest for a short pulse). A series
// at an order where the twin has no term that is weaker than a
// residual line within 8 orders is that line's sidebands, not a finding: a revolution in which
// a defect appears holds its pulse train for part of the revolution only, and the lines
// spread to their neighbours. One flag per series for the run; later revolutions that show it
// again update it.
//
// Only revolutions turned at a steady speed are analysed (at most 1/16 of one off the median
// pace: a start's ramp passes, a static run's stops at every position do not): the diagnosis
// is the dynamic run's. Revolutions are numbered from the run's first motion either way.
//
// Single-threaded (the twin's thread feeds it); cheap: one FFT of one revolution per
// revolution.

#include <cstdint>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "wavebench/analysis/amplitude_spectrum.hpp"
#include "wavebench/model/gear_params.hpp"
#include "wavebench/twin/twin_point.hpp"

namespace wavebench::twin {

struct ResidualWatchOptions {
  double relative_band = 0.25;
  double floor_factor = 1.0;
  double noise_factor = 8.0;
  double sensor_noise_rad =
      0;                 // the configured output encoder noise (BenchDescription); 0 = measure
  int max_harmonic = 8;  // a line joins a lower line's series up to this multiple
  // A series at an order where the twin has no term whose lines are
  // weaker than 1/sideband_ratio × a residual line within max_sideband orders is that line's
  // sidebands: a line whose amplitude changes within the revolution (a defect's onset) spreads
  // to its neighbours (at ±k, c·|sin(πk·f)|/(πk) for a line present a fraction f of it: never
  // more than the line itself).
  int max_sideband = 8;
  double sideband_ratio = 0.7;
  int max_order = 0;  // highest order watched; 0 = the revolution's angular Nyquist
  std::size_t min_samples_per_revolution = 64;
  // Back-steps of θ1 smaller than this are jitter (skipped); larger ones start a new
  // revolution in the new direction [rad of the input].
  double reversal_rad = 0.01;
};

struct FlaggedLine {
  int order = 0;  // cycles per output revolution
  double amplitude_rad = 0;
  double band_rad = 0;
  double predicted_rad = 0;  // the twin's own line there
};

struct RankedSource {
  std::string source;  // the twin's TE term (TeTerm::source)
  std::string family;  // its family as configs name it (tangential_output, ...)
  double share = 0;    // of the model's prediction at the order (analysis::PeakSource::share)
  double predicted_amplitude_rad = 0;
  int harmonic = 1;  // 1: the term sits at the order; n: the order is its n-th harmonic
};

struct DiagnosticFlag {
  int order = 0;  // the series' fundamental
  double amplitude_rad = 0, band_rad = 0;
  int first_revolution = 0;  // 1-based, counted from the run's start
  double first_t_s = 0;      // bench time at the end of that revolution
  double onset_t_s = 0;      // bench time at its start
  int last_revolution = 0;
  int revolutions = 0;                // how many revolutions showed it
  std::vector<FlaggedLine> lines;     // the series in its first revolution, by order
  std::vector<RankedSource> sources;  // what the twin's model puts at `order`, first = ranked first
  std::string suspect;                // what that ranking points at, for people
};

struct RevolutionSummary {
  int revolution = 0;
  double t_start_s = 0, t_end_s = 0;
  std::size_t samples = 0;
  double residual_rms_rad = 0;  // of the revolution (mean removed)
  double floor_rad = 0;         // σ used for the band
  double largest_ratio = 0;     // max_k |R_k| / band_k
  int largest_ratio_order = 0;
};

struct DiagnosticReport {
  ResidualWatchOptions options;
  std::vector<RevolutionSummary> revolutions;  // analysed
  // Whole revolutions not analysed: not turned at a steady speed (a static run's stops) or
  // with too few samples.
  int unsteady_revolutions = 0;
  std::vector<DiagnosticFlag> flags;
};

class ResidualWatch {
 public:
  // twin: the twin's gear (its TE terms rank the sources); ratio: the bench's N.
  ResidualWatch(const model::GearParams& twin, double ratio, ResidualWatchOptions options = {});
  ~ResidualWatch();
  ResidualWatch(const ResidualWatch&) = delete;
  ResidualWatch& operator=(const ResidualWatch&) = delete;

  // Called with each new flag (not with updates of an existing one), on the feeding thread.
  void on_flag(std::function<void(const DiagnosticFlag&)> callback) {
    on_flag_ = std::move(callback);
  }

  // The next point in order; points without a measured or predicted TE are skipped.
  void feed(const TwinPoint& point);
  const DiagnosticReport& report() const { return report_; }

 private:
  void analyse_revolution();
  void restart(const TwinPoint& point);

  model::GearParams twin_;
  double ratio_;
  ResidualWatchOptions options_;
  std::unique_ptr<analysis::SpectrumAnalyser> analyser_;
  std::vector<int> known_orders_;
  std::vector<TwinPoint> window_;
  double start_theta_ = 0;
  int direction_ = 0;  // +1 / -1 once θ1 has moved, 0 before
  int revolution_ = 0;
  DiagnosticReport report_;
  std::function<void(const DiagnosticFlag&)> on_flag_;
};

// The flag's source ranking at `order` from the twin's TE terms.
std::vector<RankedSource> rank_sources_at_order(const model::GearParams& twin, double ratio,
                                                int order, int max_harmonic);
// "tangential_output", ... (the config's family names).
std::string te_family_name(model::TeFamily family);
// What a family's excess points at, for people ("a local tooth defect on the Flexspline ...").
std::string suspect_for(const RankedSource& first);
// One revolution's expected band and lines above it, given the residual's and the twin's
// amplitude spectra over exactly that revolution (bin k = output order k) and σ.
std::vector<FlaggedLine> lines_above_band(const std::vector<double>& residual,
                                          const std::vector<double>& predicted, double floor_rad,
                                          const ResidualWatchOptions& options, int max_order,
                                          double* largest_ratio, int* largest_ratio_order);
// Grouped by harmonic series (see above); each group sorted by order, its fundamental first.
std::vector<std::vector<FlaggedLine>> harmonic_series(std::vector<FlaggedLine> lines,
                                                      int max_harmonic);
// The twin's TE terms' orders of the output revolution (integer ones, ascending).
std::vector<int> model_orders(const model::GearParams& twin, double ratio);
// Drops the series that are sidebands of a residual line (see ResidualWatchOptions); a
// sideband series of a flagged line joins its series. residual: the revolution's residual
// spectrum (bin k = order k); known_orders: model_orders().
std::vector<std::vector<FlaggedLine>> attach_sidebands(std::vector<std::vector<FlaggedLine>> series,
                                                       const std::vector<double>& residual,
                                                       const std::vector<int>& known_orders,
                                                       const ResidualWatchOptions& options);

nlohmann::json to_json(const DiagnosticFlag& flag);
nlohmann::json to_json(const DiagnosticReport& report);
// One line for logs and the console: "order 202 (2.4 × its band, 8.1 arcsec): ...".
std::string describe(const DiagnosticFlag& flag);

}  // namespace wavebench::twin
