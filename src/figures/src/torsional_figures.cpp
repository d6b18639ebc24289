// The locked-output torsional procedure's figures (src/procedures/src/torsional_procedure.cpp; the
// catalogues' definitions, bench.md §4). Each is an uncertain figure object.
#include <array>

#include "figure_units.hpp"
#include "wavebench/figures/figure_registry.hpp"

namespace wavebench::figures {

namespace {

using strict_yaml::Dimension;
using units::kArcmin;
using units::kNmPerRad;

constexpr FigureDeclaration angle(const char* name, const char* key, const char* label,
                                  SpecLimit limit, FleetTrend fleet) {
  return {.name = name,
          .procedure = "torsional",
          .path = key,
          .uncertainty_path = key,
          .label = label,
          .dimension = Dimension::kAngle,
          .unit = "arcmin",
          .per_unit = kArcmin,
          .display_unit = "arcmin",
          .display_scale = 1,
          .display_digits = 4,
          .limit = limit,
          .fleet = fleet,
          .plot = PlotKind::kValue};
}

constexpr FigureDeclaration stiffness(const char* name, const char* key, const char* label,
                                      SpecLimit limit, FleetTrend fleet) {
  return {.name = name,
          .procedure = "torsional",
          .path = key,
          .uncertainty_path = key,
          .label = label,
          .dimension = Dimension::kStiffness,
          .unit = "N*m/rad",
          .per_unit = kNmPerRad,
          .display_unit = "N·m/rad",
          .display_scale = 1,
          .display_digits = 5,
          .limit = limit,
          .fleet = fleet,
          .plot = PlotKind::kValue};
}

constexpr std::array kFigures{
    angle("hysteresis_loss", "torsional.hysteresis_loss_arcmin", "Hysteresis loss",
          {LimitKind::kUpper, "hysteresis_loss_arcmin"},
          {"hysteresis_loss", "hysteresis_loss_arcmin",
           "hysteresis loss (torsional: twist width at zero torque)"}),
    angle("locked_lost_motion", "torsional.lost_motion_arcmin", "Lost motion (locked output)",
          {LimitKind::kUpper, "locked_lost_motion_arcmin"},
          {"lost_motion", "lost_motion_arcmin",
           "lost motion (lost-motion procedure, else torsional)"}),
    angle("locked_backlash", "torsional.backlash_arcmin", "Backlash (locked output)", {}, {}),
    stiffness("min_locked_k1", "torsional.stiffness.k1_nm_per_rad",
              "Torsional stiffness K1, locked output (minimum)",
              {LimitKind::kLower, "min_locked_stiffness_nm_per_rad"},
              {"k1", "k1_nm_per_rad", "stiffness K1"}),
    stiffness("locked_k2", "torsional.stiffness.k2_nm_per_rad",
              "Torsional stiffness K2, locked output", {}, {"k2", "k2_nm_per_rad", "stiffness K2"}),
    stiffness("locked_k3", "torsional.stiffness.k3_nm_per_rad",
              "Torsional stiffness K3, locked output", {}, {"k3", "k3_nm_per_rad", "stiffness K3"}),
};

}  // namespace

std::span<const FigureDeclaration> torsional_figures() {
  return kFigures;
}

}  // namespace wavebench::figures
