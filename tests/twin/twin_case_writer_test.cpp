// write_twin_case_yaml() against load_twin_case(): every shipped twin case survives a round
// trip with the same parameters.
#include "wavebench/config/twin_case_writer.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <variant>

#include "wavebench/config/twin_case.hpp"

namespace wavebench::config {
namespace {

void expect_same_sinusoid(const model::Sinusoid& a, const model::Sinusoid& b) {
  EXPECT_DOUBLE_EQ(a.offset, b.offset);
  EXPECT_DOUBLE_EQ(a.amplitude, b.amplitude);
  EXPECT_DOUBLE_EQ(a.frequency_hz, b.frequency_hz);
  EXPECT_DOUBLE_EQ(a.phase_rad, b.phase_rad);
}

void expect_same(const TwinCase& a, const TwinCase& b) {
  const auto& g = a.gear;
  const auto& h = b.gear;
  EXPECT_EQ(g.name, h.name);
  EXPECT_DOUBLE_EQ(g.geometry.ratio, h.geometry.ratio);
  EXPECT_EQ(g.geometry.z_flex, h.geometry.z_flex);
  EXPECT_EQ(g.geometry.z_circ, h.geometry.z_circ);
  EXPECT_EQ(g.geometry.wave_number, h.geometry.wave_number);
  EXPECT_EQ(g.geometry.direction_sign, h.geometry.direction_sign);
  EXPECT_DOUBLE_EQ(g.inertia_input, h.inertia_input);
  EXPECT_DOUBLE_EQ(g.inertia_output, h.inertia_output);
  EXPECT_DOUBLE_EQ(g.viscous_input, h.viscous_input);
  EXPECT_DOUBLE_EQ(g.viscous_output, h.viscous_output);
  ASSERT_EQ(g.te_terms.size(), h.te_terms.size());
  for (std::size_t i = 0; i < g.te_terms.size(); ++i) {
    EXPECT_EQ(g.te_terms[i].source, h.te_terms[i].source);
    EXPECT_EQ(g.te_terms[i].family, h.te_terms[i].family);
    EXPECT_DOUBLE_EQ(g.te_terms[i].amplitude_rad, h.te_terms[i].amplitude_rad);
    EXPECT_DOUBLE_EQ(g.te_terms[i].order_input, h.te_terms[i].order_input);
    EXPECT_DOUBLE_EQ(g.te_terms[i].order_output, h.te_terms[i].order_output);
    EXPECT_DOUBLE_EQ(g.te_terms[i].phase_rad, h.te_terms[i].phase_rad);
  }
  EXPECT_EQ(g.stiffness.law.index(), h.stiffness.law.index());
  EXPECT_EQ(g.stiffness.modulation.size(), h.stiffness.modulation.size());
  EXPECT_EQ(g.stiffness.mean_stiffness.has_value(), h.stiffness.mean_stiffness.has_value());
  if (const auto* t = std::get_if<model::ThreeSegmentStiffness>(&g.stiffness.law)) {
    const auto& u = std::get<model::ThreeSegmentStiffness>(h.stiffness.law);
    EXPECT_DOUBLE_EQ(t->k1, u.k1);
    EXPECT_DOUBLE_EQ(t->t1, u.t1);
    EXPECT_DOUBLE_EQ(t->k2, u.k2);
    EXPECT_DOUBLE_EQ(t->t2, u.t2);
    EXPECT_DOUBLE_EQ(t->k3, u.k3);
  }
  if (const auto* f = std::get_if<model::FadingMemoryStiffness>(&g.stiffness.law)) {
    const auto& u = std::get<model::FadingMemoryStiffness>(h.stiffness.law);
    EXPECT_DOUBLE_EQ(f->c, u.c);
    EXPECT_DOUBLE_EQ(f->memory_decay, u.memory_decay);
  }
  if (const auto* hb = std::get_if<model::HystereticBranchStiffness>(&g.stiffness.law)) {
    const auto& u = std::get<model::HystereticBranchStiffness>(h.stiffness.law);
    EXPECT_DOUBLE_EQ(hb->a_load, u.a_load);
    EXPECT_DOUBLE_EQ(hb->c_unload, u.c_unload);
  }
  EXPECT_DOUBLE_EQ(g.backlash.total_rad, h.backlash.total_rad);
  EXPECT_DOUBLE_EQ(g.backlash.smoothing_rad, h.backlash.smoothing_rad);
  EXPECT_EQ(g.damping.damping_ratio.has_value(), h.damping.damping_ratio.has_value());
  EXPECT_EQ(g.damping.coefficient.has_value(), h.damping.coefficient.has_value());
  EXPECT_EQ(g.friction.index(), h.friction.index());
  EXPECT_EQ(g.input.index(), h.input.index());
  EXPECT_DOUBLE_EQ(g.nominal_input_speed, h.nominal_input_speed);
  expect_same_sinusoid(g.load.output_torque, h.load.output_torque);
  expect_same_sinusoid(g.load.drive_ripple, h.load.drive_ripple);
  EXPECT_DOUBLE_EQ(g.load.output_drag_coulomb, h.load.output_drag_coulomb);
  EXPECT_EQ(g.load.brake.has_value(), h.load.brake.has_value());
  EXPECT_EQ(a.solver.method, b.solver.method);
  EXPECT_DOUBLE_EQ(a.solver.rtol, b.solver.rtol);
  EXPECT_DOUBLE_EQ(a.solver.t_end, b.solver.t_end);
  EXPECT_DOUBLE_EQ(a.solver.transient, b.solver.transient);
  EXPECT_DOUBLE_EQ(a.solver.sample_rate, b.solver.sample_rate);
  EXPECT_EQ(a.solver.locate_events, b.solver.locate_events);
}

TEST(TwinCaseWriter, EveryShippedCaseRoundTrips) {
  const auto dir = std::filesystem::path(WAVEBENCH_SOURCE_DIR) / "configs" / "twin";
  int cases = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    if (entry.path().extension() != ".yaml") continue;
    SCOPED_TRACE(entry.path().string());
    const TwinCase original = load_twin_case(entry.path());
    const std::string text = write_twin_case_yaml(original, "round trip\nof a shipped case");
    EXPECT_EQ(text.rfind("# round trip\n# of a shipped case\n", 0), 0u);
    const TwinCase again = parse_twin_case(text, entry.path().filename().string());
    expect_same(original, again);
    ++cases;
  }
  EXPECT_GE(cases, 4);
}

TEST(TwinCaseWriter, KinematicTraceAndCustomOrdersRoundTrip) {
  TwinCase c = load_twin_case(std::filesystem::path(WAVEBENCH_SOURCE_DIR) / "configs" / "twin" /
                              "bench-unit-seed004.yaml");
  model::KinematicInput k;
  k.trace_t = {0, 0.001, 0.002, 0.0031};
  k.trace_theta = {0, 0.0104, 0.021, 0.0333333333333333};
  c.gear.input = k;
  c.gear.te_terms.push_back({"encoder zero offset", model::TeFamily::kCustom, 1.3e-5, 0, 0, -1.5});
  model::PowderBrakeParams brake;
  brake.rated_current_a = 2.0;
  brake.rated_torque_nm = 5.0;
  brake.threshold_current_a = 0.05;
  brake.hysteresis_a = 0.07;
  brake.tau_rise_s = 0.05;
  brake.tau_fall_s = 0.09;
  brake.heat_capacity_j_per_k = 40;
  brake.heat_loss_w_per_k = 4;
  c.gear.load.brake = brake;
  c.gear.load.brake_current_a = 1.0;
  const TwinCase again = parse_twin_case(write_twin_case_yaml(c));
  expect_same(c, again);
  const auto& k2 = std::get<model::KinematicInput>(again.gear.input);
  ASSERT_EQ(k2.trace_theta.size(), 4u);
  EXPECT_DOUBLE_EQ(k2.trace_theta[3], k.trace_theta[3]);
  const auto& b2 = *again.gear.load.brake;
  EXPECT_DOUBLE_EQ(b2.rated_torque_nm, 5.0);
  EXPECT_DOUBLE_EQ(b2.hysteresis_a, 0.07);
  EXPECT_DOUBLE_EQ(b2.tau_fall_s, 0.09);
  EXPECT_DOUBLE_EQ(b2.heat_loss_w_per_k, 4);
  EXPECT_DOUBLE_EQ(again.gear.load.brake_current_a, 1.0);
}

}  // namespace
}  // namespace wavebench::config
