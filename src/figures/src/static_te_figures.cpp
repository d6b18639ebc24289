// The static TE procedure's figures (src/procedures/src/static_te_procedure.cpp).
#include <array>

#include "figure_units.hpp"
#include "wavebench/figures/figure_registry.hpp"

namespace wavebench::figures {

namespace {

using strict_yaml::Dimension;
using units::kArcmin;

constexpr std::array kFigures{
    FigureDeclaration{
        .name = "static_te_p2p",
        .procedure = "static",
        .path = "static[*].p2p_arcmin",
        .uncertainty_path = "static[*].uncertainty.p2p_arcmin",
        .label = "Static transmission error, peak-to-peak",
        .dimension = Dimension::kAngle,
        .unit = "arcmin",
        .per_unit = kArcmin,
        .display_unit = "arcmin",
        .display_scale = 1,
        .display_digits = 4,
        .limit = {LimitKind::kUpper, "static_p2p_arcmin"},
        .fleet = {"static_te_p2p", "static_p2p_arcmin",
                  "static TE peak to peak, the largest pass (--direction/--load: one pass)"},
        .plot = PlotKind::kPerElement},
    FigureDeclaration{.name = "static_te_std",
                      .procedure = "static",
                      .path = "static[*].std_arcmin",
                      .uncertainty_path = "static[*].uncertainty.std_arcmin",
                      .label = "Static transmission error, standard deviation",
                      .dimension = Dimension::kAngle,
                      .unit = "arcmin",
                      .per_unit = kArcmin,
                      .display_unit = "arcmin",
                      .display_scale = 1,
                      .display_digits = 4,
                      .limit = {LimitKind::kUpper, "static_std_arcmin"},
                      .fleet = {},
                      .plot = PlotKind::kPerElement},
    FigureDeclaration{.name = "static_te_abs_mean",
                      .procedure = "static",
                      .path = "static[*].mean_arcmin",
                      .uncertainty_path = "static[*].uncertainty.mean_arcmin",
                      .label = "Static transmission error, |mean|",
                      .dimension = Dimension::kAngle,
                      .unit = "arcmin",
                      .per_unit = kArcmin,
                      .display_unit = "arcmin",
                      .display_scale = 1,
                      .display_digits = 4,
                      .limit = {LimitKind::kUpperOfMagnitude, "static_abs_mean_arcmin"},
                      .fleet = {},
                      .plot = PlotKind::kPerElement},
    FigureDeclaration{.name = "static_lost_motion",
                      .procedure = "static",
                      .path = "lost_motion[*].max_abs_arcmin",
                      .uncertainty_path = "lost_motion[*].uncertainty.max_abs_arcmin",
                      .label = "Lost motion (static test), largest",
                      .dimension = Dimension::kAngle,
                      .unit = "arcmin",
                      .per_unit = kArcmin,
                      .display_unit = "arcmin",
                      .display_scale = 1,
                      .display_digits = 4,
                      .limit = {LimitKind::kUpper, "static_lost_motion_arcmin"},
                      .fleet = {"static_lost_motion", "static_lost_motion_arcmin",
                                "static procedure: largest |reverse - forward| over its loads"},
                      .plot = PlotKind::kPerElement},
};

}  // namespace

std::span<const FigureDeclaration> static_te_figures() {
  return kFigures;
}

}  // namespace wavebench::figures
