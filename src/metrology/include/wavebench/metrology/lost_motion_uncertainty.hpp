#pragma once
// The uncertainty of the brake-ladder lost-motion figures (bench.md §4): lost motion, backlash,
// K1/K2/K3 and T1/T2 come out of a nonlinear fit (breakpoint search), so the point
// uncertainties are carried through it by Monte Carlo: every point's twist perturbed by its
// combined standard, the fit redone `draws` times, the spread of each figure its standard
// uncertainty. The fit's own RMS residual is added to every point's standard (what the
// three-segment law does not explain is as good as noise to it). The spread is then shared out
// among the sources in proportion to their variance at the points, which is exact for a fit
// that is linear in the twists with the same mix of sources at every point, as here.

#include <cstdint>
#include <nlohmann/json.hpp>
#include <span>
#include <vector>

#include "wavebench/metrology/lost_motion_fit.hpp"
#include "wavebench/metrology/uncertainty_budget.hpp"

namespace wavebench::metrology {

struct LostMotionUncertaintyInputs {
  double input_resolution_rad = 0;      // θ_in step; 0: unknown
  double output_resolution_rad = 0;     // θ_out step
  double ratio = 1;                     // N: θ_in enters the twist divided by it
  std::vector<double> twist_noise_rad;  // per record point: its window's noise (may be empty)
  int draws = 24;
  std::uint64_t seed = 0x10517;
};

struct LostMotionUncertainty {  // values and budgets in the units of results.json
  UncertainFigure lost_motion_arcmin, backlash_arcmin;
  UncertainFigure k1_nm_per_rad, k2_nm_per_rad, k3_nm_per_rad, t1_nm, t2_nm;
};

LostMotionUncertainty lost_motion_uncertainty(std::span<const TorqueTwistPoint> record,
                                              const LostMotionOptions& options,
                                              const LostMotionResult& result,
                                              const LostMotionUncertaintyInputs& inputs);

// {"lost_motion_arcmin", "backlash_arcmin"} and, for the stiffness object,
// {"k1_nm_per_rad", ..., "t2_nm"}: UncertainFigure objects (to_json).
nlohmann::json fit_uncertainty_json(const LostMotionUncertainty& u);
nlohmann::json stiffness_uncertainty_json(const LostMotionUncertainty& u);

}  // namespace wavebench::metrology
