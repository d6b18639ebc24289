#include "wavebench/fleet/fleet_figures.hpp"

#include <stdexcept>

namespace wavebench::fleet {

const std::vector<FleetFigure>& fleet_figures() {
  static const std::vector<FleetFigure> figures = {
      {"static_te_p2p", "static_p2p_arcmin", "arcmin", "static_p2p_arcmin", false,
       "static TE peak to peak, the largest pass (--direction/--load: one pass)"},
      {"static_lost_motion", "static_lost_motion_arcmin", "arcmin", "static_lost_motion_arcmin",
       false, "static procedure: largest |reverse - forward| over its loads"},
      {"lost_motion", "lost_motion_arcmin", "arcmin", "lost_motion_arcmin", false,
       "lost motion (lost-motion procedure, else torsional)"},
      {"k1", "k1_nm_per_rad", "N*m/rad", "min_stiffness_nm_per_rad", true, "stiffness K1"},
      {"k2", "k2_nm_per_rad", "N*m/rad", "", false, "stiffness K2"},
      {"k3", "k3_nm_per_rad", "N*m/rad", "", false, "stiffness K3"},
      {"dynamic_te_p2p", "dynamic_p2p_arcsec", "arcsec", "dynamic_p2p_arcsec", false,
       "dynamic TE peak to peak"},
      {"dynamic_te_rms", "dynamic_rms_arcsec", "arcsec", "dynamic_rms_arcsec", false,
       "dynamic TE RMS"},
      {"twin_residual_before", "twin_residual_before_arcsec", "arcsec", "", false,
       "twin residual RMS before calibration"},
      {"twin_residual_after", "twin_residual_after_arcsec", "arcsec", "twin_residual_rms_arcsec",
       false, "twin residual RMS after calibration"},
  };
  return figures;
}

const FleetFigure& find_fleet_figure(const std::string& name) {
  std::string names;
  for (const auto& f : fleet_figures()) {
    if (name == f.name) return f;
    names += (names.empty() ? "" : ", ") + std::string(f.name);
  }
  throw std::invalid_argument("figure: got '" + name + "', expected one of " + names);
}

}  // namespace wavebench::fleet
