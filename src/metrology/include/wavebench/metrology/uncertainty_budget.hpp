#pragma once
// Measurement uncertainty as the GUM (JCGM 100) builds it, for every figure a procedure reports
// (bench.md §4): each contribution is a standard uncertainty in the figure's own unit, already
// multiplied by its sensitivity coefficient; contributions are taken as uncorrelated and combined
// by root sum of squares; the expanded uncertainty is U = k·u_c with k = 2 (about 95 %).
//
// Hand-written: the arithmetic is a few lines, and no Debian package carries a GUM budget.

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace wavebench::metrology {

inline constexpr double kCoverageFactor = 2.0;

struct UncertaintyContribution {
  std::string source;     // "encoder quantisation", "noise after averaging", ...
  char evaluation = 'B';  // 'A' statistical (repeats, scatter), 'B' otherwise (GUM 4.2, 4.3)
  double standard = 0;    // standard uncertainty, in the figure's unit, sensitivity applied
  // True when it differs from one repeat of the procedure to the next (window noise, where the
  // output settled): the spread between repeats already contains it, so a figure averaged over
  // repeats replaces it by that spread (repeat_combination). False for what stays the same in
  // every repeat (an encoder's quantisation at the same counts, a model's limits).
  bool varies_between_repeats = false;
};

struct UncertainFigure {
  double value = 0;
  std::vector<UncertaintyContribution> budget;
  double coverage_factor = kCoverageFactor;

  UncertainFigure& add(std::string source, double standard, char evaluation = 'B',
                       bool varies_between_repeats = false);
  double combined_standard() const;  // u_c: root sum of squares of the budget
  double expanded() const;           // U = k·u_c
};

// A quantisation step q read as a uniform distribution of width q: q/√12 (GUM 4.3.7, F.2.2.1).
double quantisation_standard(double step);
// A rectangular distribution of half-width a: a/√3 (GUM 4.3.7).
double rectangular_standard(double half_width);
// The standard deviation of the mean of n values with sample standard deviation s: s/√n.
// Zero for n < 2 (no spread to see).
double standard_of_mean(double sample_std, int n);
// Sample standard deviation (divides by n − 1) of values; zero for fewer than two.
double sample_std(const std::vector<double>& values);

// {"value", "expanded", "k", "combined_standard",
//  "budget": [{"source", "type", "standard", "varies_between_repeats"}]},
// every number multiplied by `scale` (rad → arcmin, say) so a figure is reported in its unit.
nlohmann::json to_json(const UncertainFigure& figure, double scale = 1.0);
// True for an object in the to_json shape (value, expanded and a budget array).
bool is_uncertain_figure_json(const nlohmann::json& j);
// The figure back from to_json's shape, every number divided by `scale`. Throws
// std::invalid_argument when `j` is not in that shape.
UncertainFigure uncertain_figure_from_json(const nlohmann::json& j, double scale = 1.0);

// ISO 14253-1 decision rules against one limit, with the expanded uncertainty as the guard
// band: conformance is proven only when the whole interval [value − U, value + U] is on the
// good side, non-conformance only when it is wholly on the bad side; otherwise undecided.
enum class LimitDecision { kPass, kFail, kUndecided };
const char* decision_name(LimitDecision decision);  // "PASS", "FAIL", "UNDECIDED"
LimitDecision decide_upper_limit(const UncertainFigure& figure, double max);
LimitDecision decide_lower_limit(const UncertainFigure& figure, double min);

}  // namespace wavebench::metrology
