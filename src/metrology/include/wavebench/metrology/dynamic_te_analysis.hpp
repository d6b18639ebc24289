#pragma once
// Dynamic TE (bench.md §4): constant input speed, at least one whole output revolution sampled
// on SYNC. TE against time and output angle; mean, peak-to-peak, RMS; the order spectrum of
// the whole revolutions (the record resampled on the measured output angle) and its average
// over single revolutions (Welch); peaks named; the twin's components above Nyquist listed as
// aliased with the frequency they fold to. A record is reduced as it is acquired
// (dynamic_te_record.hpp): its memory is one double per sample, for the whole-record FFT.

#include <nlohmann/json.hpp>
#include <span>
#include <string>
#include <vector>

#include "wavebench/analysis/amplitude_spectrum.hpp"
#include "wavebench/metrology/gear_sense.hpp"
#include "wavebench/metrology/uncertainty_budget.hpp"

namespace wavebench::metrology {

struct GearTeeth {
  int z_flex = 0;       // z_F
  int z_circ = 0;       // z_C
  int wave_number = 2;  // U
};

// A component the twin predicts: e = A sin(a·θ1 + b·θ2 + φ); frequency (a + b/N)·f_H.
struct PredictedComponent {
  std::string name;
  double order_input = 0;   // a
  double order_output = 0;  // b
  double amplitude_rad = 0;
};

struct DynamicTeOptions {
  analysis::Window window = analysis::Window::kHann;
  int max_peaks = 12;
  double min_relative_amplitude = 1e-3;
  int harmonics = 3;            // named harmonics of output 1/rev and of the mesh
  double name_tolerance = 0.0;  // output orders; 0 = 1.5 bins of the order spectrum
  // Encoder steps for the uncertainty budget (0: unknown, left out).
  double input_resolution_rad = 0;   // θ_in
  double output_resolution_rad = 0;  // θ_out
  int monte_carlo_draws = 20;        // for p2p and RMS (each draw perturbs every sample)
  // The order spectra keep their bins up to this output order (0: all); peaks are searched
  // over all of them either way.
  double max_order_kept = 0;
};

struct NamedPeak {
  std::string name;         // "output 1/rev", "mesh x2", a twin component's name, or "unnamed"
  double order_output = 0;  // cycles per output revolution
  double order_input = 0;   // cycles per wave-generator revolution
  double frequency_hz = 0;  // at the run's mean speed
  double amplitude_arcsec = 0;
  UncertainFigure amplitude;  // arcsec
};

struct AliasedComponent {
  std::string name;
  double frequency_hz = 0;  // (a + b/N)·f_H
  double folded_hz = 0;     // where it appears in the sampled record
  double amplitude_arcsec = 0;
};

struct DynamicTeResult {
  // The trace: every kept sample of a short record, or the smallest and the largest TE of
  // each block of `trace_stride` samples (in time order) of a long one.
  std::vector<double> time_s;            // from the first sample's timestamp
  std::vector<double> output_angle_rad;  // θ2, from its first value
  std::vector<double> te_arcsec;
  std::size_t trace_stride = 1;
  std::size_t samples = 0;  // kept samples the figures are over
  double mean_arcsec = 0;
  double p2p_arcsec = 0;
  double rms_arcsec = 0;      // about the mean
  double input_speed_hz = 0;  // f_H, mean
  double sample_rate_hz = 0;  // mean, from the timestamps
  double nyquist_hz = 0;
  double output_revolutions = 0;
  std::vector<double> order_output;  // order-spectrum axis, output orders
  std::vector<double> order_amplitude_arcsec;
  double order_resolution = 0;                  // output orders per bin
  std::size_t order_points_per_revolution = 0;  // of the resampled record
  std::size_t order_revolutions = 0;            // whole revolutions the order spectrum is over
  // Welch: the amplitude spectrum of each whole output revolution on its own (Hann), power
  // averaged; bins at whole output orders. Empty with fewer than two whole revolutions.
  std::vector<double> averaged_order_output;
  std::vector<double> averaged_amplitude_arcsec;
  std::size_t averaged_revolutions = 0;
  std::size_t averaged_revolutions_dropped = 0;  // whole revolutions the average could not take
  std::vector<NamedPeak> peaks;
  std::vector<AliasedComponent> aliased;
  // mean, p2p and RMS with their budgets (arcsec). Each sample carries the encoders'
  // quantisation and the noise measured from the record's second differences (less the
  // quantisation it already contains); they are independent from sample to sample.
  UncertainFigure mean, p2p, rms;
};

// time_s from the samples' receive timestamps (strictly increasing); θ_in, θ_out unwrapped.
// Throws std::invalid_argument naming the quantity when the record is shorter than one output
// revolution, the lengths differ, or time or the output angle are not strictly monotone.
DynamicTeResult analyse_dynamic_te(std::span<const double> time_s,
                                   std::span<const double> theta_in_rad,
                                   std::span<const double> theta_out_rad, const GearSense& sense,
                                   const GearTeeth& teeth,
                                   std::span<const PredictedComponent> predicted,
                                   const DynamicTeOptions& options,
                                   analysis::SpectrumAnalyser& analyser);

// What a record's samples leave behind when it is reduced as it is acquired
// (dynamic_te_record.hpp).
struct DynamicRecordFigures {
  std::size_t samples = 0;
  double duration_s = 0;        // first to last sample
  double output_angle_rad = 0;  // turned, > 0
  double input_angle_rad = 0;   // turned, > 0
  double mean_arcsec = 0, p2p_arcsec = 0, rms_arcsec = 0;
  double second_difference_noise_arcsec = 0;  // sample_noise_from_second_differences
};

struct RevolutionAverage;

// The analysis of a reduced record: `grid` is its TE on `points_per_revolution` points per
// output revolution from the first sample, over whole revolutions (consumed: the order
// spectrum is computed in its memory); `averaged` the Welch average over all its whole
// revolutions (revolution_welch.hpp). Throws std::invalid_argument when the record turned
// less than one output revolution. The trace is left empty.
DynamicTeResult analyse_dynamic_record(const DynamicRecordFigures& figures,
                                       std::vector<double>&& grid,
                                       std::size_t points_per_revolution,
                                       const RevolutionAverage& averaged, const GearSense& sense,
                                       const GearTeeth& teeth,
                                       std::span<const PredictedComponent> predicted,
                                       const DynamicTeOptions& options);

// Spectrum of a record with irregular timestamps: linear resampling onto a uniform grid at
// the mean rate over the same span, then the amplitude spectrum.
analysis::AmplitudeSpectrum spectrum_on_timestamps(std::span<const double> time_s,
                                                   std::span<const double> signal,
                                                   analysis::Window window,
                                                   analysis::SpectrumAnalyser& analyser);

// Where a line at `frequency_hz` appears when sampled at `sample_rate_hz`.
double folded_frequency(double frequency_hz, double sample_rate_hz);

nlohmann::json to_json(const DynamicTeResult& result);

}  // namespace wavebench::metrology
