#pragma once
// How the uncertainties of measured points (each an UncertainFigure: a TE value at one settled
// position, say) carry into the figures computed from them (GUM 5.1): the mean, a difference,
// the peak-to-peak, the population standard deviation, the largest value.
//
// Contributions are matched by source name and taken as independent from point to point (the
// quantisation error, window noise and settle of one position do not repeat at the next), so
// each source's standard in the figure is sqrt(Σ (c_i u_i)²) with c_i = ∂figure/∂point_i.
//
// Peak-to-peak, maximum and standard deviation are not linear: which point is the extreme can
// change with the noise, and the p2p of n noisy points is biased upward (E[max] of a point
// plus noise is above the point). The linear part (sensitivities at the observed extremes)
// stays per source; what it misses is one more contribution, "selection of extremes (Monte
// Carlo)": every point perturbed by its combined standard (normal), the figure recomputed
// `draws` times, and sqrt(max(0, var_mc − u_lin²)) + |bias| with bias = mean_mc − observed. The
// value itself is not corrected (a catalogue's p2p is of the measured points); the bias widens
// the interval instead, which keeps the coverage at least nominal where points crowd an extreme.

#include <cstdint>
#include <span>
#include <string>

#include "wavebench/metrology/uncertainty_budget.hpp"

namespace wavebench::metrology {

inline constexpr const char* kExtremeSelectionSource = "selection of extremes (Monte Carlo)";

struct PropagationOptions {
  int draws = 400;                // Monte Carlo draws for the nonlinear figures
  std::uint64_t seed = 0x57a71c;  // fixed: the same data give the same budget
};

// Σ c_i·point_i with the sources combined as above (a weighted sum: mean, difference).
UncertainFigure weighted_sum(std::span<const UncertainFigure> points,
                             std::span<const double> weights);
UncertainFigure mean_of(std::span<const UncertainFigure> points);
UncertainFigure difference_of(const UncertainFigure& a, const UncertainFigure& b);  // a − b
// |a| with a's budget.
UncertainFigure absolute_of(const UncertainFigure& a);
// `value` scaled by `factor` (its budget too): a change of unit, a sensitivity.
UncertainFigure scaled(const UncertainFigure& a, double factor);

UncertainFigure peak_to_peak_of(std::span<const UncertainFigure> points,
                                const PropagationOptions& options = {});
UncertainFigure maximum_of(std::span<const UncertainFigure> points,
                           const PropagationOptions& options = {});
// Population standard deviation (divides by n): the RMS about the mean over a revolution.
UncertainFigure population_std_of(std::span<const UncertainFigure> points,
                                  const PropagationOptions& options = {});

// The standard uncertainty of the mean of n consecutive samples with sample standard deviation
// s whose noise may be correlated (a servo's dither, a filter in the encoder): s/√n_eff with
// n_eff = n(1 − ρ)/(1 + ρ), ρ the lag-1 autocorrelation (AR(1), clamped to [0, 0.99]; a
// negative ρ would claim better than white noise). Zero for fewer than two samples.
double standard_of_window_mean(std::span<const double> samples);

// Per-sample noise of a signal that also carries a smooth variation (a TE record in motion):
// from second differences, σ² = var(x[i+1] − 2x[i] + x[i−1]) / 6, which a line or a slow
// harmonic barely enters. Zero for fewer than four samples.
double sample_noise_from_second_differences(std::span<const double> samples);

}  // namespace wavebench::metrology
