#pragma once
// Statistical process control of one figure over a sequence of runs (individuals, n = 1):
// mean, overall sigma (sample, n - 1), the moving range, within sigma MR-bar / d2 (d2 = 1.128),
// capability Cp/Cpk on the within sigma and Pp/Ppk on the overall one against the spec limits
// that exist (one-sided specs give only the side they have), and the individuals chart's
// limits mean ± 2.66 MR-bar (= 3 MR-bar / d2). Hand-written: a few sums, no Debian library
// computes AIAG capability indices.

#include <cstddef>
#include <nlohmann/json.hpp>
#include <optional>
#include <vector>

namespace wavebench::fleet {

struct SpecLimits {
  std::optional<double> lower, upper;
};

struct SpcFigures {
  std::size_t n = 0;
  double mean = 0;
  double sigma = 0;         // overall, sample standard deviation
  double mr_bar = 0;        // mean moving range |x_i - x_{i-1}|
  double sigma_within = 0;  // mr_bar / 1.128
  double ucl = 0, lcl = 0;  // mean ± 2.66 mr_bar
  std::optional<double> cp, cpk, pp, ppk;
  // Indices of points outside [lcl, ucl] (rule 1 of the individuals chart).
  std::vector<std::size_t> out_of_control;
};

inline constexpr double kD2 = 1.128;
inline constexpr double kIndividualsFactor = 2.66;

// Throws std::invalid_argument when fewer than 2 values are given (no moving range), or when
// lower >= upper.
SpcFigures spc_figures(const std::vector<double>& values, const SpecLimits& limits);

nlohmann::json to_json(const SpcFigures& spc);

}  // namespace wavebench::fleet
