// gear: tooth counts, ratio, direction, inertias, viscous losses (model.md §1-2).
#include <cmath>
#include <string>

#include "twin_sections.hpp"
#include "wavebench/config/config_error.hpp"

namespace wavebench::config {
namespace {

std::string format_number(double v) {
  std::string s = std::to_string(v);
  s.erase(s.find_last_not_of('0') + 1);
  if (!s.empty() && s.back() == '.') s.pop_back();
  return s;
}

}  // namespace

void parse_gear_section(YamlSection& s, model::GearParams& gear) {
  auto& g = gear.geometry;
  const bool has_flex = s.has("z_flex");
  const bool has_circ = s.has("z_circ");
  if (has_flex != has_circ) {
    const std::string missing = has_flex ? "z_circ" : "z_flex";
    s.fail(missing, "", "an integer tooth count (z_flex and z_circ come together)");
  }
  if (has_flex) {
    g.z_flex = static_cast<int>(s.integer("z_flex", kIntMin, kIntMax));
    g.z_circ = static_cast<int>(s.integer("z_circ", kIntMin, kIntMax));
    s.require_within("z_flex", g.z_flex, 1, kMaxOrder, "a tooth count");
    s.require_within("z_circ", g.z_circ, 1, kMaxOrder, "a tooth count");
    if (g.z_circ <= g.z_flex) {
      s.fail("z_circ", s.value_text("z_circ"),
             "more teeth than z_flex = " + std::to_string(g.z_flex) +
                 " (Circular Spline fixed, Flexspline output)");
    }
  }
  const double teeth_ratio =
      has_flex ? static_cast<double>(g.z_flex) / static_cast<double>(g.z_circ - g.z_flex) : 0.0;
  if (s.has("ratio")) {
    g.ratio = s.positive_quantity("ratio", Dimension::kDimensionless);
    s.require_within("ratio", g.ratio, 1e-3, 1e5, "a reduction ratio");
    if (has_flex && std::abs(g.ratio - teeth_ratio) > 1e-6 * teeth_ratio) {
      s.fail("ratio", s.value_text("ratio"),
             "z_flex/(z_circ - z_flex) = " + format_number(teeth_ratio) +
                 " for z_flex = " + std::to_string(g.z_flex) +
                 ", z_circ = " + std::to_string(g.z_circ) + " (or leave the ratio out)");
    }
  } else if (has_flex) {
    g.ratio = teeth_ratio;
  } else {
    s.fail("ratio", "", "a reduction ratio N > 0, or the tooth counts z_flex and z_circ");
  }

  g.wave_number = static_cast<int>(
      s.integer_or("wave_number", kIntMin, kIntMax, has_flex ? g.z_circ - g.z_flex : 2));
  s.require_within("wave_number", g.wave_number, 1, 100, "a wave number");
  g.direction_sign = static_cast<int>(s.integer_or("direction", kIntMin, kIntMax, 1));
  if (g.direction_sign != 1 && g.direction_sign != -1) {
    s.fail("direction", s.value_text("direction"), "+1 or -1");
  }

  // A vanishing inertia makes the gear infinitely stiff for the solver: it never finishes.
  gear.inertia_input = s.positive_quantity("inertia_input", Dimension::kInertia);
  s.require_within("inertia_input", gear.inertia_input, 1e-9, 1e6, "an inertia [kg*m^2]");
  gear.inertia_output = s.positive_quantity("inertia_output", Dimension::kInertia);
  s.require_within("inertia_output", gear.inertia_output, 1e-9, 1e6, "an inertia [kg*m^2]");
  gear.viscous_input = s.non_negative_quantity_or("viscous_input", Dimension::kDamping, 0.0);
  gear.viscous_output = s.non_negative_quantity_or("viscous_output", Dimension::kDamping, 0.0);
  s.finish();
}

}  // namespace wavebench::config
