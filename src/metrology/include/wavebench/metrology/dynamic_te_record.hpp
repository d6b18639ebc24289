#pragma once
// A dynamic-TE record reduced as it is acquired (issue #12): a run of hours must not keep its
// samples. What a sample leaves behind: running sums for mean, p2p, RMS and the second
// differences; a bounded trace (min and max per block); its TE on a uniform grid of the
// output angle, one double per sample, because the whole-record order spectrum needs every
// point at once (finish() turns the grid into that spectrum in place); and the Welch average
// over every whole revolution (revolution_welch.hpp), which needs one revolution at a time.
//
// add() allocates nothing (the grid and the trace are sized from the shape up front), so it may
// run on the acquisition thread.

#include <cstddef>
#include <span>
#include <vector>

#include "wavebench/metrology/dynamic_te_analysis.hpp"
#include "wavebench/metrology/dynamic_te_input.hpp"
#include "wavebench/metrology/revolution_welch.hpp"

namespace wavebench::metrology {

struct DynamicTeRecordShape {
  // The sign in which the raw θ_out advances (+1 or −1); samples that do not are skipped.
  double output_direction = 1;
  // The order grid: points per output revolution (≥ 8), and the whole revolutions it holds
  // (≥ 1). Revolutions beyond them still enter the figures and the Welch average, not the
  // whole-record spectrum.
  std::size_t points_per_revolution = 0;
  std::size_t max_revolutions = 0;
  // Where the Welch average transforms a revolution: on its own worker while add() runs on the
  // acquisition thread, else where add() runs.
  RevolutionWelch::Transform welch = RevolutionWelch::Transform::kWherePut;
  analysis::SpectrumAnalyser* welch_analyser = nullptr;  // kWherePut: the caller's, else own
  // The trace keeps the smallest and largest TE of every `trace_stride` kept samples.
  std::size_t trace_stride = 1;
  // Trace rows reserved up front. When a record runs longer than its stride was set for, the
  // blocks are merged in pairs and the stride doubled, so the trace never outgrows it.
  std::size_t trace_capacity = 0;
};

// The smallest 2·3·5-smooth number ≥ n: an order grid FFTW transforms fast at any length.
std::size_t smooth_size_at_least(std::size_t n);

class DynamicTeRecord {
 public:
  // Throws std::invalid_argument when the shape is out of range or the grid would exceed
  // max_grid_points.
  DynamicTeRecord(const GearSense& sense, const DynamicTeRecordShape& shape,
                  std::size_t max_grid_points = std::size_t{1} << 27);

  // A sample as acquired: filtered and counted (DynamicTeSampleFilter), then reduced.
  void add(const storage::SyncSample& sample) noexcept;
  // A sample already selected: time [s] strictly after the previous one, the output past it.
  // Throws std::invalid_argument naming what is not monotone.
  void add_kept(double time_s, double theta_in_rad, double theta_out_rad);

  const DynamicTeSampleCounts& counts() const { return filter_.counts(); }
  std::size_t samples_offered() const { return offered_; }
  std::size_t samples_kept() const { return kept_; }

  // The analysis of the record (dynamic_te_analysis.hpp); the grid is consumed. Throws
  // std::invalid_argument when the record is shorter than one output revolution.
  DynamicTeResult finish(const GearTeeth& teeth, std::span<const PredictedComponent> predicted,
                         const DynamicTeOptions& options);

 private:
  struct TracePoint {
    double t = 0, angle = 0, te = 0;
  };
  void extend_grid(double angle, double te);
  void put_grid_point(double te);
  void close_trace_block();
  void halve_trace();

  GearSense sense_;
  DynamicTeRecordShape shape_;
  DynamicTeSampleFilter filter_;
  std::size_t offered_ = 0, kept_ = 0;
  double sign_ = 1;  // of the model output angle's advance
  double first_t_ = 0, theta2_0_ = 0, theta_in_0_ = 0, last_theta_in_ = 0;
  double last_t_ = 0, last_angle_ = 0, last_te_ = 0;
  // TE [arcsec] running figures: Welford mean and M2, extremes, second differences.
  double mean_ = 0, m2_ = 0, lo_ = 0, hi_ = 0, second_ss_ = 0, te_1_ = 0, te_2_ = 0;
  std::vector<double> grid_;  // TE [arcsec] at j·2π/P of output angle
  std::size_t grid_capacity_ = 0;
  std::size_t grid_points_ = 0;  // made so far, in the grid or past its end
  RevolutionWelch welch_;
  double grid_step_ = 0;
  std::vector<double> trace_t_, trace_angle_, trace_te_;
  std::size_t trace_stride_ = 1;
  std::size_t block_count_ = 0;
  TracePoint block_min_, block_max_;
};

}  // namespace wavebench::metrology
