// The endurance procedure's figures (src/procedures/src/endurance_procedure.cpp): its summary over
// the analysed output revolutions.
#include <array>

#include "figure_units.hpp"
#include "wavebench/figures/figure_registry.hpp"

namespace wavebench::figures {

namespace {

using strict_yaml::Dimension;
using units::kArcsec;

constexpr FigureDeclaration te(const char* name, const char* key, const char* label) {
  return {.name = name,
          .procedure = "endurance",
          .path = key,
          .uncertainty_path = "",
          .label = label,
          .dimension = Dimension::kAngle,
          .unit = "arcsec",
          .per_unit = kArcsec,
          .display_unit = "arcsec",
          .display_scale = 1,
          .display_digits = 4,
          .limit = {},
          .fleet = {},
          .plot = PlotKind::kValue};
}

constexpr std::array kFigures{
    te("endurance_p2p_first", "endurance.summary.p2p_first_arcsec",
       "TE peak-to-peak, first revolution"),
    te("endurance_p2p_last", "endurance.summary.p2p_last_arcsec",
       "TE peak-to-peak, last revolution"),
    te("endurance_p2p_max", "endurance.summary.p2p_max_arcsec", "TE peak-to-peak, largest"),
    te("endurance_mean_drift", "endurance.summary.mean_drift_arcsec",
       "TE mean, last revolution less first"),
};

}  // namespace

std::span<const FigureDeclaration> endurance_figures() {
  return kFigures;
}

}  // namespace wavebench::figures
