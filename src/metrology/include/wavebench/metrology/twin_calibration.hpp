#pragma once
// The twin beside the bench (bench.md §5): the residual between measured and predicted TE,
// and the calibration fit of the twin's TE harmonics, stiffness and backlash to a run.

#include <nlohmann/json.hpp>
#include <span>
#include <string>
#include <vector>

#include "wavebench/analysis/amplitude_spectrum.hpp"
#include "wavebench/metrology/static_te_statistics.hpp"

namespace wavebench::metrology {

// Measured − predicted TE over a record: figures only, so that a record of hours costs what
// one sample does (its samples are in twin.csv).
struct TwinResidual {
  double mean_arcsec = 0;
  double rms_arcsec = 0;  // of the residual as it is (an offset is a residual too)
  double p2p_arcsec = 0;
  std::size_t samples = 0;
};

// The residual one pair at a time.
class TwinResidualSum {
 public:
  void add(double measured_te_rad, double predicted_te_rad);
  // Throws std::invalid_argument when fewer than 8 pairs were added.
  TwinResidual result() const;

 private:
  double sum_ = 0, squares_ = 0, lo_ = 0, hi_ = 0;
  std::size_t n_ = 0;
};

// Throws std::invalid_argument when the lengths differ or there are fewer than 8 samples.
TwinResidual twin_residual(std::span<const double> measured_te_rad,
                           std::span<const double> predicted_te_rad);

// One term of the ordered harmonic basis: sin(a·θ1 + b·θ2 + φ), θ2 in the model's convention.
struct HarmonicOrder {
  std::string name;
  double order_input = 0;   // a
  double order_output = 0;  // b
};

struct FittedHarmonic {
  std::string name;
  double order_input = 0;
  double order_output = 0;
  double amplitude_rad = 0;  // A ≥ 0
  double phase_rad = 0;      // φ in (−π, π]
};

struct HarmonicFit {
  double offset_rad = 0;
  std::vector<FittedHarmonic> harmonics;
  double rms_residual_rad = 0;
  double evaluate(double theta1, double theta2) const;
};

// Linear least squares of TE on {1, sin(a·θ1 + b·θ2), cos(a·θ1 + b·θ2)} per order. Throws
// std::invalid_argument when there are fewer samples than unknowns or an order is repeated.
HarmonicFit fit_te_harmonics(std::span<const double> theta1_rad, std::span<const double> theta2_rad,
                             std::span<const double> te_rad, std::span<const HarmonicOrder> orders);

// The same fit with extra regressors beside the harmonic basis (the twin's calibration puts
// the flank sign there for the backlash and the spring twist for the compliance), each a column
// as long as te_rad; their coefficients come back in `coefficients`, in order.
struct HarmonicRegression {
  HarmonicFit fit;
  std::vector<double> coefficients;
};
HarmonicRegression fit_te_harmonics(std::span<const double> theta1_rad,
                                    std::span<const double> theta2_rad,
                                    std::span<const double> te_rad,
                                    std::span<const HarmonicOrder> orders,
                                    std::span<const std::vector<double>> regressors);

// Backlash and secant stiffness from a static TE run at two loads (the lowest and the highest):
// backlash = mean lost motion at the lowest load; shift = |loaded − unloaded mean TE|,
// averaged over the directions (they shift opposite ways); K = ΔT / shift.
struct StiffnessBacklashEstimate {
  double backlash_rad = 0;
  double shift_rad = 0;
  double load_nm = 0;  // ΔT between the two loads
  double stiffness_nm_per_rad = 0;
};
// Throws std::invalid_argument when the run lacks two loads or a forward/reverse pair.
StiffnessBacklashEstimate estimate_stiffness_backlash(const StaticTeResult& run);

nlohmann::json to_json(const HarmonicFit& fit);
nlohmann::json to_json(const TwinResidual& residual);

}  // namespace wavebench::metrology
