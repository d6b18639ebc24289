// defects: what a simulated unit can be given to prove the twin's diagnosis (issue #11).
// Only the simulated bench's plant takes them (model::GearDefects); a twin refuses them.
#include <numbers>
#include <string>

#include "twin_sections.hpp"

namespace wavebench::config {
namespace {

constexpr double kMaxDefectAngleRad = 0.01;  // 34 arcmin: far beyond any tooth error
constexpr double kMaxOnsetRev = 1e6;

double onset_rev(YamlSection& s) {
  const double onset = s.quantity_or("onset", Dimension::kAngle, 0.0);
  s.require_within("onset", onset, 0, kMaxOnsetRev * 2 * std::numbers::pi,
                   "output revolutions turned before the defect appears (e.g. \"3 rev\")");
  return onset / (2 * std::numbers::pi);
}

model::ToothDefect parse_tooth(YamlSection& s, const model::GearGeometry& g) {
  model::ToothDefect d;
  const std::string part = s.choice("part", {"flexspline", "circular_spline"});
  d.part =
      part == "flexspline" ? model::DefectPart::kFlexspline : model::DefectPart::kCircularSpline;
  const int z = d.part == model::DefectPart::kFlexspline ? g.z_flex : g.z_circ;
  if (z <= 0) {
    s.fail("part", part, "gear.z_flex and gear.z_circ in the gear section (a tooth needs them)");
  }
  d.tooth = static_cast<int>(s.integer_or("tooth", 0, z - 1, 0));
  d.amplitude_rad = s.quantity("amplitude", Dimension::kAngle);
  if (d.amplitude_rad == 0) s.fail("amplitude", s.value_text("amplitude"), "a non-zero angle");
  s.require_within("amplitude", d.amplitude_rad, -kMaxDefectAngleRad, kMaxDefectAngleRad,
                   "the pulse's peak in TE");
  d.width = s.number_or("width", 1e-3, 1.0, d.width);
  d.onset_rev = onset_rev(s);
  return d;
}

model::RisingOnceRevDefect parse_rising(YamlSection& s) {
  model::RisingOnceRevDefect d;
  d.growth_rad_per_rev = s.quantity("growth_per_rev", Dimension::kAngle);
  if (d.growth_rad_per_rev == 0) {
    s.fail("growth_per_rev", s.value_text("growth_per_rev"), "a non-zero angle per revolution");
  }
  s.require_within("growth_per_rev", d.growth_rad_per_rev, -kMaxDefectAngleRad, kMaxDefectAngleRad,
                   "the 1/rev amplitude added per output revolution");
  d.phase_rad = s.quantity_or("phase", Dimension::kAngle, 0.0);
  d.onset_rev = onset_rev(s);
  return d;
}

}  // namespace

void parse_defects_section(std::vector<YamlSection> items, model::GearParams& gear) {
  for (auto& item : items) {
    const std::string kind = item.choice("kind", {"tooth", "rising_once_per_rev"});
    if (kind == "tooth") {
      gear.defects.teeth.push_back(parse_tooth(item, gear.geometry));
    } else {
      gear.defects.rising_once_per_rev.push_back(parse_rising(item));
    }
    item.finish();
  }
}

}  // namespace wavebench::config
