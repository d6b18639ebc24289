// The dynamic TE procedure's figures (src/procedures/src/dynamic_te_procedure.cpp).
#include <array>

#include "figure_units.hpp"
#include "wavebench/figures/figure_registry.hpp"

namespace wavebench::figures {

namespace {

using strict_yaml::Dimension;
using units::kArcsec;

constexpr FigureDeclaration te(const char* name, const char* key, const char* uncertainty,
                               const char* label, const char* limit, FleetTrend fleet) {
  return {.name = name,
          .procedure = "dynamic",
          .path = key,
          .uncertainty_path = uncertainty,
          .label = label,
          .dimension = Dimension::kAngle,
          .unit = "arcsec",
          .per_unit = kArcsec,
          .display_unit = "arcsec",
          .display_scale = 1,
          .display_digits = 4,
          .limit = {LimitKind::kUpper, limit},
          .fleet = fleet,
          .plot = PlotKind::kValue};
}

constexpr std::array kFigures{
    te("dynamic_te_p2p", "dynamic.p2p_arcsec", "dynamic.uncertainty.p2p_arcsec",
       "Dynamic transmission error, peak-to-peak", "dynamic_p2p_arcsec",
       {"dynamic_te_p2p", "dynamic_p2p_arcsec", "dynamic TE peak to peak"}),
    te("dynamic_te_rms", "dynamic.rms_arcsec", "dynamic.uncertainty.rms_arcsec",
       "Dynamic transmission error, RMS", "dynamic_rms_arcsec",
       {"dynamic_te_rms", "dynamic_rms_arcsec", "dynamic TE RMS"}),
};

}  // namespace

std::span<const FigureDeclaration> dynamic_te_figures() {
  return kFigures;
}

}  // namespace wavebench::figures
