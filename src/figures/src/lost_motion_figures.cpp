// The lost-motion procedure's figures (src/procedures/src/lost_motion_procedure.cpp).
#include <array>

#include "figure_units.hpp"
#include "wavebench/figures/figure_registry.hpp"

namespace wavebench::figures {

namespace {

using strict_yaml::Dimension;
using units::kArcmin;
using units::kNmPerRad;

constexpr FigureDeclaration stiffness(const char* name, const char* key, const char* uncertainty,
                                      const char* label, SpecLimit limit, FleetTrend fleet) {
  return {.name = name,
          .procedure = "lost-motion",
          .path = key,
          .uncertainty_path = uncertainty,
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
    FigureDeclaration{.name = "lost_motion",
                      .procedure = "lost-motion",
                      .path = "lost_motion_fit.lost_motion_arcmin",
                      .uncertainty_path = "lost_motion_fit.uncertainty.lost_motion_arcmin",
                      .label = "Lost motion",
                      .dimension = Dimension::kAngle,
                      .unit = "arcmin",
                      .per_unit = kArcmin,
                      .display_unit = "arcmin",
                      .display_scale = 1,
                      .display_digits = 4,
                      .limit = {LimitKind::kUpper, "lost_motion_arcmin"},
                      .fleet = {"lost_motion", "lost_motion_arcmin",
                                "lost motion (lost-motion procedure, else torsional)"},
                      .plot = PlotKind::kValue},
    stiffness("min_k1", "lost_motion_fit.stiffness.k1_nm_per_rad",
              "lost_motion_fit.stiffness.uncertainty.k1_nm_per_rad",
              "Torsional stiffness K1 (minimum)", {LimitKind::kLower, "min_stiffness_nm_per_rad"},
              {"k1", "k1_nm_per_rad", "stiffness K1"}),
    stiffness("k2", "lost_motion_fit.stiffness.k2_nm_per_rad",
              "lost_motion_fit.stiffness.uncertainty.k2_nm_per_rad", "Torsional stiffness K2", {},
              {"k2", "k2_nm_per_rad", "stiffness K2"}),
    stiffness("k3", "lost_motion_fit.stiffness.k3_nm_per_rad",
              "lost_motion_fit.stiffness.uncertainty.k3_nm_per_rad", "Torsional stiffness K3", {},
              {"k3", "k3_nm_per_rad", "stiffness K3"}),
};

}  // namespace

std::span<const FigureDeclaration> lost_motion_figures() {
  return kFigures;
}

}  // namespace wavebench::figures
