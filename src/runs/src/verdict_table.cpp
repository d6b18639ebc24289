#include "verdict_table.hpp"

#include <array>
#include <numbers>
#include <sstream>

namespace wavebench::runs {

namespace {

using strict_yaml::Dimension;

constexpr double kArcmin = std::numbers::pi / 10800;
constexpr double kArcsec = kArcmin / 60;

constexpr std::array<VerdictFigure, 12> kFigures{{
    {"static_te_p2p", "static_p2p_arcmin", Dimension::kAngle, "arcmin", kArcmin,
     "static[*].p2p_arcmin", false, false, "Static transmission error, peak-to-peak", "arcmin"},
    {"static_te_std", "static_std_arcmin", Dimension::kAngle, "arcmin", kArcmin,
     "static[*].std_arcmin", false, false, "Static transmission error, standard deviation",
     "arcmin"},
    {"static_te_abs_mean", "static_abs_mean_arcmin", Dimension::kAngle, "arcmin", kArcmin,
     "static[*].mean_arcmin", false, true, "Static transmission error, |mean|", "arcmin"},
    {"static_lost_motion", "static_lost_motion_arcmin", Dimension::kAngle, "arcmin", kArcmin,
     "lost_motion[*].max_abs_arcmin", false, false, "Lost motion (static test), largest", "arcmin"},
    {"lost_motion", "lost_motion_arcmin", Dimension::kAngle, "arcmin", kArcmin,
     "lost_motion_fit.lost_motion_arcmin", false, false, "Lost motion", "arcmin"},
    {"min_k1", "min_stiffness_nm_per_rad", Dimension::kStiffness, "N*m/rad", 1,
     "lost_motion_fit.stiffness.k1_nm_per_rad", true, false, "Torsional stiffness K1 (minimum)",
     "N·m/rad"},
    {"dynamic_te_p2p", "dynamic_p2p_arcsec", Dimension::kAngle, "arcsec", kArcsec,
     "dynamic.p2p_arcsec", false, false, "Dynamic transmission error, peak-to-peak", "arcsec"},
    {"dynamic_te_rms", "dynamic_rms_arcsec", Dimension::kAngle, "arcsec", kArcsec,
     "dynamic.rms_arcsec", false, false, "Dynamic transmission error, RMS", "arcsec"},
    // The locked-output torsional test (the catalogues' definitions, bench.md §4).
    {"hysteresis_loss", "hysteresis_loss_arcmin", Dimension::kAngle, "arcmin", kArcmin,
     "torsional.hysteresis_loss_arcmin", false, false, "Hysteresis loss", "arcmin"},
    {"locked_lost_motion", "locked_lost_motion_arcmin", Dimension::kAngle, "arcmin", kArcmin,
     "torsional.lost_motion_arcmin", false, false, "Lost motion (locked output)", "arcmin"},
    {"min_locked_k1", "min_locked_stiffness_nm_per_rad", Dimension::kStiffness, "N*m/rad", 1,
     "torsional.stiffness.k1_nm_per_rad", true, false,
     "Torsional stiffness K1, locked output (minimum)", "N·m/rad"},
    // The calibrated twin's residual: a model-fit figure, without a stated uncertainty.
    {"twin_residual_rms", "twin_residual_rms_arcsec", Dimension::kAngle, "arcsec", kArcsec,
     "twin.calibration.rms_after_arcsec", false, false, "Twin residual after calibration, RMS",
     "arcsec"},
}};

std::vector<std::string> split(const std::string& path) {
  std::vector<std::string> out;
  std::string part;
  std::istringstream in(path);
  while (std::getline(in, part, '.')) out.push_back(part);
  return out;
}

// "reverse 60 N·m", "mesh": what an array element is, from the keys that name one.
std::string element_label(const nlohmann::json& e) {
  std::ostringstream s;
  if (!e.is_object()) return {};
  if (const auto d = e.find("direction"); d != e.end() && d->is_string())
    s << " " << d->get<std::string>();
  if (const auto n = e.find("name"); n != e.end() && n->is_string())
    s << " " << n->get<std::string>();
  if (const auto l = e.find("load_nm"); l != e.end() && l->is_number()) {
    s << " " << l->get<double>() << " N·m";
  }
  return s.str();
}

void walk(const nlohmann::json& node, const std::vector<std::string>& parts, std::size_t i,
          const std::string& path, const std::string& where, std::vector<FoundFigure>& out) {
  if (!node.is_object()) return;
  std::string key = parts[i];
  const bool every = key.size() > 3 && key.ends_with("[*]");
  if (every) key.resize(key.size() - 3);
  const auto it = node.find(key);
  if (it == node.end()) return;
  const std::string here = path.empty() ? key : path + "." + key;
  if (every) {
    if (!it->is_array()) return;
    for (std::size_t k = 0; k < it->size(); ++k) {
      const std::string p = here + "[" + std::to_string(k) + "]";
      if (i + 1 < parts.size()) walk((*it)[k], parts, i + 1, p, p + element_label((*it)[k]), out);
    }
    return;
  }
  if (i + 1 < parts.size()) {
    walk(*it, parts, i + 1, here, where, out);
    return;
  }
  FoundFigure f;
  f.path = here;
  f.where = where.empty() ? here : where;
  const auto u = node.find("uncertainty");
  if (u != node.end() && u->is_object() && u->contains(key) &&
      procedures::is_uncertain_figure_json((*u)[key])) {
    f.figure = procedures::uncertain_figure_from_json((*u)[key]);
    f.uncertainty_stated = true;
  } else if (procedures::is_uncertain_figure_json(*it)) {
    f.figure = procedures::uncertain_figure_from_json(*it);
    f.uncertainty_stated = true;
  } else if (it->is_number()) {
    f.figure.value = it->get<double>();
  } else {
    return;  // null (not computed) or another shape: nothing to judge
  }
  out.push_back(std::move(f));
}

}  // namespace

std::span<const VerdictFigure> verdict_figures() {
  return kFigures;
}

std::vector<FoundFigure> find_figures(const nlohmann::json& results, const std::string& path) {
  std::vector<FoundFigure> out;
  const auto parts = split(path);
  if (!parts.empty()) walk(results, parts, 0, "", "", out);
  return out;
}

}  // namespace wavebench::runs
