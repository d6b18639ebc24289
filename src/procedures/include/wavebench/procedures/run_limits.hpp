#pragma once
// The verdict of a run against the limits the request gives (its product spec's, with the
// request's own "limits" on top): every limit that applies to the run's results is checked;
// none applying means no verdict. Which figure each limit judges, and where results.json holds
// it, is one table (src/procedures/src/verdict_table.cpp):
//
//   static_p2p_arcmin, static_std_arcmin, static_abs_mean_arcmin  each static pass
//   static_lost_motion_arcmin     the largest |forward − reverse| at any position, per load
//   lost_motion_arcmin            lost motion at ±x % of rated (lost-motion procedure)
//   min_stiffness_nm_per_rad      K1 of the lost-motion fit
//   dynamic_p2p_arcsec, dynamic_rms_arcsec
//   twin_residual_rms_arcsec      RMS of measured − predicted TE of the calibrated twin
//                                 (twin.calibration.rms_after_arcsec; runs with calibration)
//
// Each check is guard-banded as ISO 14253-1 describes, with the figure's expanded uncertainty
// U (k = 2): PASS when the whole interval [value − U, value + U] is on the good side of the
// limit, FAIL when it is wholly on the bad side, UNDECIDED when the limit lies inside it.

#include <nlohmann/json.hpp>
#include <optional>

#include "wavebench/metrology/uncertainty_budget.hpp"

namespace wavebench::procedures {

// How an UNDECIDED check counts for the acceptance of the unit (`pass`), chosen by the spec.
// ISO 14253-1: the supplier proves conformance, so by default undecided is not a pass.
enum class UndecidedCounts { kFail, kPass, kUndecided };
const char* undecided_counts_name(UndecidedCounts counts);  // "fail", "pass", "undecided"

// Throws std::invalid_argument naming an unknown limit or a value that is not a number > 0.
void validate_limits(const nlohmann::json& limits);

struct LimitVerdict {
  // The decision over every check: FAIL when one failed, else UNDECIDED when one was, else
  // PASS; none when no limit applied.
  std::optional<metrology::LimitDecision> decision;
  // Acceptance: PASS true, FAIL false, UNDECIDED as `UndecidedCounts` says (kUndecided: none).
  std::optional<bool> pass;
  // {limit, value, measured, expanded, k, uncertainty_stated, what, path, decision, pass}
  nlohmann::json checks = nlohmann::json::array();
};

LimitVerdict check_limits(const nlohmann::json& limits, const nlohmann::json& results,
                          UndecidedCounts undecided = UndecidedCounts::kFail);

}  // namespace wavebench::procedures
