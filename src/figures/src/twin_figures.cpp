// The calibrated twin's figures (the twin beside the bench, any procedure): model-fit
// figures without a stated uncertainty.
#include <array>

#include "figure_units.hpp"
#include "wavebench/figures/figure_registry.hpp"

namespace wavebench::figures {

namespace {

using strict_yaml::Dimension;
using units::kArcsec;

constexpr FigureDeclaration residual(const char* name, const char* key, const char* label,
                                     SpecLimit limit, FleetTrend fleet) {
  return {.name = name,
          .procedure = "*",
          .path = key,
          .uncertainty_path = "",
          .label = label,
          .dimension = Dimension::kAngle,
          .unit = "arcsec",
          .per_unit = kArcsec,
          .display_unit = "arcsec",
          .display_scale = 1,
          .display_digits = 4,
          .limit = limit,
          .fleet = fleet,
          .plot = PlotKind::kValue};
}

constexpr std::array kFigures{
    residual("twin_residual_before", "twin.calibration.rms_before_arcsec",
             "Twin residual before calibration, RMS", {},
             {"twin_residual_before", "twin_residual_before_arcsec",
              "twin residual RMS before calibration"}),
    residual("twin_residual_rms", "twin.calibration.rms_after_arcsec",
             "Twin residual after calibration, RMS",
             {LimitKind::kUpper, "twin_residual_rms_arcsec"},
             {"twin_residual_after", "twin_residual_after_arcsec",
              "twin residual RMS after calibration"}),
};

}  // namespace

std::span<const FigureDeclaration> twin_figures() {
  return kFigures;
}

}  // namespace wavebench::figures
