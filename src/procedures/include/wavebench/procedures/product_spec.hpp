#pragma once
// A product spec: the acceptance limits of one gear model (configs/specs/NAME.yaml), each
// written with its unit. A run that names a spec is checked against its limits (run_limits)
// and gets a verdict, PASS, FAIL or UNDECIDED (guard-banded by each figure's uncertainty).
//
//   model: CSF-25-100-2A-GR
//   description: ...
//   undecided: fail                  how an UNDECIDED check counts: fail (default), pass or
//                                    undecided (no acceptance decision)
//   limits:
//     static_te_p2p: 1.0 arcmin      -> static_p2p_arcmin
//     lost_motion: 1.0 arcmin        -> lost_motion_arcmin (lost-motion procedure) ...
//     lost_motion_at: 3 %            ... measured at ± this fraction of rated torque
//     min_k1: 3.1e4 N*m/rad          -> min_stiffness_nm_per_rad
//     dynamic_te_p2p: 90 arcsec      -> dynamic_p2p_arcsec
//     twin_residual_rms: 3 arcsec    -> twin_residual_rms_arcsec (the calibrated twin's)
//   (also static_te_std, static_te_abs_mean, static_lost_motion, dynamic_te_rms)

#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "wavebench/procedures/run_limits.hpp"

namespace wavebench::procedures {

struct SpecLimit {
  std::string key;    // as written in the spec ("static_te_p2p")
  std::string limit;  // the run_limits key it sets ("static_p2p_arcmin")
  double value = 0;   // in `unit`
  std::string unit;   // "arcmin", "arcsec", "N*m/rad"
};

struct ProductSpec {
  std::string name;  // the file's stem
  std::string model;
  std::string description;
  std::vector<SpecLimit> limits;
  // Lost motion is measured at ± this fraction of rated torque (lost_motion_at).
  std::optional<double> lost_motion_fraction;
  // How a check whose limit lies inside the figure's uncertainty interval counts.
  UndecidedCounts undecided = UndecidedCounts::kFail;

  // {run_limits key: value} as check_limits reads them.
  nlohmann::json run_limits() const;
  // {"name", "model", "description", "lost_motion_at_percent" (or null), "undecided",
  //  "limits": [{"key", "limit", "value", "unit"}, ...]}
  nlohmann::json to_json() const;
};

// Throws std::invalid_argument naming the file, the key, the value and what was expected.
ProductSpec parse_product_spec(const std::string& yaml_text, const std::string& name,
                               const std::string& source);
ProductSpec load_product_spec(const std::filesystem::path& file);

// specs/ of the shipped configs (config::shipped_config_dir()).
std::filesystem::path default_specs_dir();

// The names of the *.yaml files in `dir`, sorted; none when it does not exist.
std::vector<std::string> product_spec_names(const std::filesystem::path& dir);

// The spec a request names. Throws std::invalid_argument naming `spec`, the value and what was
// expected: a name of at most 64 characters of [A-Za-z0-9._-] (not starting with a dot), one of
// the specs in `dir` (listed).
ProductSpec find_product_spec(const std::filesystem::path& dir, const std::string& name);

}  // namespace wavebench::procedures
