#pragma once
// Pass/fail of a run against the limits the request gives (options "limits"): every limit
// that applies to the procedure's results is checked; none applying means no verdict.
//
//   static_p2p_arcmin, static_std_arcmin, static_abs_mean_arcmin  each static pass
//   static_lost_motion_arcmin     the largest |reverse − forward| at any position and load
//   lost_motion_arcmin            lost motion at ±x % of rated (lost-motion procedure)
//   min_stiffness_nm_per_rad      K1 of the lost-motion fit
//   dynamic_p2p_arcsec, dynamic_rms_arcsec
//   twin_residual_rms_arcsec      RMS of measured − predicted TE of the calibrated twin
//                                 (twin.calibration.rms_after_arcsec; runs with calibration)

#include <nlohmann/json.hpp>
#include <optional>

namespace wavebench::runs {

// Throws std::invalid_argument naming an unknown limit or a value that is not a number > 0.
void validate_limits(const nlohmann::json& limits);

struct LimitVerdict {
  std::optional<bool> pass;                         // none when no limit applied
  nlohmann::json checks = nlohmann::json::array();  // {limit, value, measured, pass}
};

LimitVerdict check_limits(const nlohmann::json& limits, const nlohmann::json& results);

}  // namespace wavebench::runs
