// stiffness: one of the seven laws of model.md §4, plus the angle-periodic modulation.
#include <string>

#include "twin_sections.hpp"
#include "wavebench/config/config_error.hpp"

namespace wavebench::config {
namespace {

std::vector<model::StiffnessHarmonic> parse_harmonics(YamlSection& s, const std::string& key,
                                                      Dimension amplitude_dimension) {
  std::vector<model::StiffnessHarmonic> out;
  for (auto& h : s.section_list(key)) {
    model::StiffnessHarmonic harmonic;
    harmonic.amplitude = h.quantity("amplitude", amplitude_dimension);
    harmonic.order_input = h.quantity_or("order_input", Dimension::kDimensionless, 0.0);
    harmonic.order_output = h.quantity_or("order_output", Dimension::kDimensionless, 0.0);
    h.require_within("order_input", harmonic.order_input, -kMaxOrder, kMaxOrder, "an order");
    h.require_within("order_output", harmonic.order_output, -kMaxOrder, kMaxOrder, "an order");
    if (harmonic.order_input == 0 && harmonic.order_output == 0) {
      h.fail("order_input", h.value_text("order_input"),
             "a non-zero order_input or order_output (an order-0 term is part of the mean)");
    }
    harmonic.phase_rad = h.quantity_or("phase", Dimension::kAngle, 0.0);
    h.finish();
    out.push_back(harmonic);
  }
  return out;
}

model::TableStiffness parse_table(YamlSection& s) {
  model::TableStiffness t;
  t.twist_rad = s.quantity_list("twist", Dimension::kAngle);
  t.torque_nm = s.quantity_list("torque", Dimension::kTorque);
  if (t.twist_rad.size() < 2) {
    s.fail("twist", s.value_text("twist"), "at least two points, starting at 0");
  }
  if (t.torque_nm.size() != t.twist_rad.size()) {
    s.fail("torque", s.value_text("torque"),
           std::to_string(t.twist_rad.size()) + " values, one per twist point");
  }
  if (t.twist_rad.front() != 0.0 || t.torque_nm.front() != 0.0) {
    s.fail("twist", s.value_text("twist"),
           "a curve starting at twist 0, torque 0 (it is odd-extended)");
  }
  for (std::size_t i = 1; i < t.twist_rad.size(); ++i) {
    if (!(t.twist_rad[i] > t.twist_rad[i - 1])) {
      s.fail("twist", s.value_text("twist"), "strictly ascending twist values");
    }
    if (t.torque_nm[i] < t.torque_nm[i - 1]) {
      s.fail("torque", s.value_text("torque"), "torque values that never decrease");
    }
  }
  return t;
}

}  // namespace

void parse_stiffness_section(YamlSection& s, model::StiffnessParams& stiffness) {
  const std::string form = s.choice("form", {"linear_periodic", "cubic", "three_segment", "table",
                                             "hysteretic_branches", "fading_memory", "bouc_wen"});
  if (form == "linear_periodic") {
    model::LinearPeriodicStiffness law;
    law.k0 = s.positive_quantity("k0", Dimension::kStiffness);
    law.harmonics = parse_harmonics(s, "harmonics", Dimension::kStiffness);
    stiffness.law = law;
  } else if (form == "cubic") {
    model::CubicStiffness law;
    law.k1 = s.positive_quantity("k1", Dimension::kStiffness);
    law.k3 = s.quantity_or("k3", Dimension::kCubicStiffness, 0.0);
    stiffness.law = law;
  } else if (form == "three_segment") {
    model::ThreeSegmentStiffness law;
    law.k1 = s.positive_quantity("k1", Dimension::kStiffness);
    law.t1 = s.positive_quantity("t1", Dimension::kTorque);
    law.k2 = s.positive_quantity("k2", Dimension::kStiffness);
    law.t2 = s.positive_quantity("t2", Dimension::kTorque);
    law.k3 = s.positive_quantity("k3", Dimension::kStiffness);
    if (!(law.t2 > law.t1)) {
      s.fail("t2", s.value_text("t2"), "a torque above t1 = " + s.value_text("t1"));
    }
    stiffness.law = law;
  } else if (form == "table") {
    stiffness.law = parse_table(s);
  } else if (form == "hysteretic_branches") {
    // Seed 001's fit: K(x) = A x^2 + B x + C in N*m/arcsec with x in arcsec, kept as written.
    model::HystereticBranchStiffness law;
    YamlSection load = s.section("loading");
    law.a_load = load.quantity("a", Dimension::kDimensionless);
    law.b_load = load.quantity("b", Dimension::kDimensionless);
    law.c_load = load.quantity("c", Dimension::kDimensionless);
    load.finish();
    YamlSection unload = s.section("unloading");
    law.a_unload = unload.quantity("a", Dimension::kDimensionless);
    law.b_unload = unload.quantity("b", Dimension::kDimensionless);
    law.c_unload = unload.quantity("c", Dimension::kDimensionless);
    unload.finish();
    if (!(law.c_load > 0)) load.fail("c", load.value_text("c"), "a stiffness at zero twist > 0");
    if (!(law.c_unload > 0)) {
      unload.fail("c", unload.value_text("c"), "a stiffness at zero twist > 0");
    }
    stiffness.law = law;
  } else if (form == "fading_memory") {
    model::FadingMemoryStiffness law;
    law.a = s.quantity("a", Dimension::kCubicStiffness);
    law.b = s.quantity("b", Dimension::kQuadraticStiffness);
    law.c = s.positive_quantity("c", Dimension::kStiffness);
    law.memory_gain = s.quantity("memory_gain", Dimension::kStiffness);
    law.memory_decay = s.positive_quantity("memory_decay", Dimension::kRate);
    stiffness.law = law;
  } else {
    model::BoucWenStiffness law;
    law.k = s.positive_quantity("k", Dimension::kStiffness);
    law.alpha = s.quantity_or("alpha", Dimension::kDimensionless, 0.5);
    if (!(law.alpha >= 0 && law.alpha <= 1)) {
      s.fail("alpha", s.value_text("alpha"), "a fraction in [0, 1]");
    }
    law.beta = s.quantity("beta", Dimension::kDimensionless);
    law.gamma = s.quantity("gamma", Dimension::kDimensionless);
    law.n = s.quantity_or("n", Dimension::kDimensionless, 1.0);
    if (!(law.n >= 1)) s.fail("n", s.value_text("n"), "an exponent >= 1");
    stiffness.law = law;
  }
  if (s.has("modulation") && (form == "linear_periodic" || form == "hysteretic_branches" ||
                              form == "fading_memory" || form == "bouc_wen")) {
    s.fail("modulation", s.value_text("modulation"),
           "no modulation for form " + form +
               " (forms cubic, three_segment and table take it; linear_periodic has harmonics)");
  }
  stiffness.modulation = parse_harmonics(s, "modulation", Dimension::kDimensionless);
  stiffness.mean_stiffness = s.optional_quantity("mean", Dimension::kStiffness);
  if (stiffness.mean_stiffness && !(*stiffness.mean_stiffness > 0)) {
    s.fail("mean", s.value_text("mean"), "a mean stiffness > 0");
  }
  s.finish();
}

void parse_backlash_section(YamlSection& s, model::BacklashParams& backlash) {
  backlash.total_rad = s.non_negative_quantity_or("total", Dimension::kAngle, 0.0);
  backlash.smoothing_rad = s.non_negative_quantity_or("smoothing", Dimension::kAngle, 0.0);
  s.finish();
}

void parse_damping_section(YamlSection& s, model::MeshDamping& damping) {
  if (s.has("ratio") && s.has("coefficient")) {
    s.fail("coefficient", s.value_text("coefficient"),
           "either ratio or coefficient, not both (ratio = " + s.value_text("ratio") + ")");
  }
  if (s.has("ratio")) {
    damping.damping_ratio = s.non_negative_quantity_or("ratio", Dimension::kDimensionless, 0.0);
  }
  if (s.has("coefficient")) {
    damping.coefficient = s.non_negative_quantity_or("coefficient", Dimension::kDamping, 0.0);
  }
  s.finish();
}

}  // namespace wavebench::config
