// te: transmission-error excitation, Fourier terms and seed 001's error sources (model.md §3).
#include <stdexcept>
#include <string>
#include <utility>

#include "twin_sections.hpp"
#include "wavebench/config/config_error.hpp"

namespace wavebench::config {
namespace {

struct FamilyName {
  const char* name;
  model::TeFamily family;
};

constexpr FamilyName kFamilies[] = {
    {"wave_generator", model::TeFamily::kWaveGenerator},
    {"housing", model::TeFamily::kHousing},
    {"tangential_output", model::TeFamily::kTangentialOutput},
    {"tangential_fixed", model::TeFamily::kTangentialFixed},
    {"output_assembly", model::TeFamily::kOutputAssembly},
    {"tooth_mesh", model::TeFamily::kToothMesh},
    {"output_once_rev", model::TeFamily::kOutputOnceRev},
    {"custom", model::TeFamily::kCustom},
};

// The orders (a, b) the table of model.md §3 gives each family.
std::pair<double, double> family_orders(model::TeFamily family, const model::GearGeometry& g) {
  const double u = g.wave_number;
  switch (family) {
    case model::TeFamily::kWaveGenerator:
      return {1, 0};
    case model::TeFamily::kHousing:
    case model::TeFamily::kTangentialFixed:
      return {u, 0};
    case model::TeFamily::kTangentialOutput:
    case model::TeFamily::kOutputAssembly:
      return {u, u};
    case model::TeFamily::kToothMesh:
      return {u * g.z_circ, 0};
    case model::TeFamily::kOutputOnceRev:
      return {0, 1};
    case model::TeFamily::kCustom:
      break;
  }
  return {0, 0};
}

model::TeTerm parse_term(YamlSection& s, const model::GearGeometry& geometry) {
  model::TeTerm term;
  term.source = s.text("source");
  term.amplitude_rad = s.quantity("amplitude", Dimension::kAngle);
  s.require_within("amplitude", term.amplitude_rad, -0.1, 0.1, "a TE amplitude [rad]");
  term.phase_rad = s.quantity_or("phase", Dimension::kAngle, 0.0);
  const std::string family =
      s.choice_or("family",
                  {"wave_generator", "housing", "tangential_output", "tangential_fixed",
                   "output_assembly", "tooth_mesh", "output_once_rev", "custom"},
                  "custom");
  for (const auto& f : kFamilies) {
    if (family == f.name) term.family = f.family;
  }
  if (term.family == model::TeFamily::kToothMesh && geometry.z_circ == 0) {
    s.fail("family", family, "a family other than tooth_mesh, or gear.z_circ to give its order");
  }
  const bool has_orders = s.has("order_input") || s.has("order_output");
  if (term.family == model::TeFamily::kCustom) {
    if (!has_orders) {
      s.fail("order_input", "",
             "the orders order_input/order_output, or a named family (the term has neither)");
    }
    term.order_input = s.quantity_or("order_input", Dimension::kDimensionless, 0.0);
    term.order_output = s.quantity_or("order_output", Dimension::kDimensionless, 0.0);
    s.require_within("order_input", term.order_input, -kMaxOrder, kMaxOrder, "an order");
    s.require_within("order_output", term.order_output, -kMaxOrder, kMaxOrder, "an order");
    return term;
  }
  const auto [a, b] = family_orders(term.family, geometry);
  term.order_input = a;
  term.order_output = b;
  // Orders given beside a family must be the family's; a mismatch is a typo, not a choice.
  if (s.has("order_input") && s.quantity("order_input", Dimension::kDimensionless) != a) {
    s.fail("order_input", s.value_text("order_input"),
           std::to_string(a) + " for family " + family + " (or family: custom)");
  }
  if (s.has("order_output") && s.quantity("order_output", Dimension::kDimensionless) != b) {
    s.fail("order_output", s.value_text("order_output"),
           std::to_string(b) + " for family " + family + " (or family: custom)");
  }
  return term;
}

void parse_error_sources(YamlSection& s, model::GearParams& gear) {
  model::ErrorSourceSet set;
  set.pitch_diameter_m = s.positive_quantity("pitch_diameter", Dimension::kLength);
  // Seed 001 writes d_w in mm and tolerances in um; a bare number is SI here as everywhere,
  // so a seed value typed without its unit would be metres. Refuse it rather than guess.
  if (set.pitch_diameter_m > 5.0) {
    s.fail("pitch_diameter", s.value_text("pitch_diameter"),
           "a diameter with its unit, e.g. \"80 mm\" (a bare number is metres)");
  }
  set.pressure_angle_rad = s.quantity("pressure_angle", Dimension::kAngle);
  if (!(set.pressure_angle_rad >= 0 && set.pressure_angle_rad < 1.2)) {
    s.fail("pressure_angle", s.value_text("pressure_angle"), "an angle in [0, 70) deg");
  }
  set.tooth_pairs_in_contact =
      s.positive_quantity("tooth_pairs_in_contact", Dimension::kDimensionless);
  auto sources = s.section_list("sources");
  if (sources.empty()) s.fail("sources", "", "a non-empty list of {name, tolerance, phase}");
  for (auto& src : sources) {
    model::ErrorSource e;
    e.name = src.text("name");
    e.tolerance_m = src.non_negative_quantity_or("tolerance", Dimension::kLength, -1.0);
    if (e.tolerance_m < 0) src.fail("tolerance", "", "a length such as \"12 um\" (required)");
    if (e.tolerance_m > 1e-3) {
      src.fail("tolerance", src.value_text("tolerance"),
               "a tolerance with its unit, e.g. \"12 um\" (a bare number is metres)");
    }
    e.phase_rad = src.quantity_or("phase", Dimension::kAngle, 0.0);
    src.finish();
    model::ErrorSourceSet one = set;
    one.sources = {e};
    try {
      (void)model::te_terms_from_error_sources(one, gear.geometry);
    } catch (const std::invalid_argument& ex) {
      src.fail("name", e.name, ex.what());
    }
    set.sources.push_back(e);
  }
  s.finish();
  for (auto& term : model::te_terms_from_error_sources(set, gear.geometry)) {
    gear.te_terms.push_back(std::move(term));
  }
}

}  // namespace

void parse_te_section(YamlSection& s, model::GearParams& gear) {
  for (auto& t : s.section_list("terms")) {
    gear.te_terms.push_back(parse_term(t, gear.geometry));
    t.finish();
  }
  if (auto es = s.optional_section("error_sources")) parse_error_sources(*es, gear);
  s.finish();
}

}  // namespace wavebench::config
