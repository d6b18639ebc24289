#pragma once
// What the dynamic TE plots draw, of a record of any length: TE against output angle and
// against time as min/max envelopes per pixel column (analysis::min_max_columns; every sample
// while there are no more than 2 × columns), and the TE spectrum (the whole record's, or
// averaged over whole output revolutions past averaged_spectrum.hpp's limit).
//
// From a sample log it is read page by page, so the memory stays that of a page and the columns
// however long the run: the same steady part as dynamic_trace() takes in memory. The pass that
// reads the run folder keeps an InputSpeedSummary; with it the steady part's bounds come from a
// few blocks of the log and the part itself is read once. Without it (or when it does not fit
// the log) three passes: the input speed's median, the part's bounds, the part.

#include <cstddef>
#include <filesystem>
#include <optional>
#include <utility>
#include <vector>

#include "wavebench/analysis/amplitude_spectrum.hpp"
#include "wavebench/analysis/min_max_columns.hpp"
#include "wavebench/report/run_folder.hpp"
#include "wavebench/report/run_plots.hpp"

namespace wavebench::report {

struct DynamicPlotData {
  analysis::DecimatedTrace te_by_angle;  // t: output angle from the first steady sample [deg]
  analysis::DecimatedTrace te_by_time;   // t: time from the first steady sample [s]
  std::optional<analysis::AmplitudeSpectrum> spectrum;  // of TE [arcsec]
  std::size_t spectrum_segments = 0;  // 0: the whole record; else the segments averaged
  double input_speed_hz = 0;          // mean f_H over the steady part
  std::size_t samples = 0;            // in the steady part
};

// At most this many windowed speeds go into the median that finds the steady speed (every
// k-th window past it): the median of a 2^19-sample subset is the steady speed to well within
// the 2 % band the steady part is taken in.
inline constexpr std::size_t kSpeedMedianWindows = std::size_t{1} << 19;

// What the first pass through a log keeps for dynamic_plot_data(), fed the records
// dynamic_trace() takes (both angles valid, each time after the previous one's): the windowed
// input speeds (every k-th for the median, as dynamic_plot_data() takes them) and, per block of
// those records (4096 blocks at most), the range of the speeds of the windows starting in it
// and where it starts. Its sizes are set from the count expected up front (the log's records);
// it fits when that count was right.
class InputSpeedSummary {
 public:
  explicit InputSpeedSummary(std::uint64_t expected_samples);
  void add(std::uint64_t record, double t, double theta_in_rad);
  bool fits(std::uint64_t angle_samples) const;

  struct Block {
    std::uint64_t record = 0;  // of its first sample
    double previous_t = 0;     // of the sample before it (-inf for the first block)
    double lo = 0, hi = 0;     // speeds of the windows starting in it
    bool any = false;
  };
  std::size_t window() const { return w_; }
  std::uint64_t block_samples() const { return block_; }
  const std::vector<Block>& blocks() const { return blocks_; }
  const std::vector<double>& median_speeds() const { return speeds_; }

 private:
  std::uint64_t expected_;
  std::size_t w_;
  std::uint64_t stride_, block_, n_ = 0;
  std::vector<std::pair<double, double>> ring_;  // (t, θ_in) of the last w + 1
  std::vector<double> speeds_;
  std::vector<Block> blocks_;
  double previous_t_;
};

// A trace in memory (results.json's "trace"). Its angle need not increase.
DynamicPlotData reduce_dynamic_trace(const DynamicTrace& trace, double ratio, std::size_t columns,
                                     analysis::SpectrumAnalyser& analyser);

// The steady part of the log's records [0, facts.records), as dynamic_trace() takes it
// (the median is exact up to kSpeedMedianWindows windows). nullopt when dynamic_trace() would
// give none. Throws as storage::read_sample_log_page.
std::optional<DynamicPlotData> dynamic_plot_data(const std::filesystem::path& log,
                                                 const SampleLogFacts& facts,
                                                 const metrology::GearSense& sense,
                                                 std::size_t columns,
                                                 analysis::SpectrumAnalyser& analyser);

}  // namespace wavebench::report
