// The shipped case configs/benches/simulated-devices-gear.yaml is the gear that was written in
// C++ (default_bench_gear) before it: every parameter the plant reads, field by field.
#include <gtest/gtest.h>

#include <cmath>

#include "../support/simulated_devices_gear.hpp"
#include "wavebench/simdevices/bench_plant.hpp"

namespace {

void near(double a, double b, const char* what) {
  EXPECT_LE(std::abs(a - b), 4e-16 * std::max(std::abs(a), std::abs(b)))
      << what << ": " << a << " vs " << b;
}

TEST(SimulatedDevicesGearCase, IsTheGearFormerlyWrittenInCpp) {
  const auto& y = wavebench::testing::simulated_devices_gear();
  const auto c = wavebench::simdevices::default_bench_gear();
  EXPECT_EQ(y.geometry.z_flex, c.geometry.z_flex);
  EXPECT_EQ(y.geometry.z_circ, c.geometry.z_circ);
  near(y.geometry.wave_number, c.geometry.wave_number, "wave_number");
  near(y.geometry.ratio, c.geometry.ratio, "ratio");
  EXPECT_EQ(y.geometry.direction_sign, c.geometry.direction_sign);
  near(y.inertia_input, c.inertia_input, "inertia_input");
  near(y.inertia_output, c.inertia_output, "inertia_output");
  near(y.viscous_input, c.viscous_input, "viscous_input");
  near(y.viscous_output, c.viscous_output, "viscous_output");
  ASSERT_EQ(y.te_terms.size(), c.te_terms.size());
  for (std::size_t i = 0; i < y.te_terms.size(); ++i) {
    EXPECT_EQ(y.te_terms[i].source, c.te_terms[i].source);
    EXPECT_EQ(y.te_terms[i].family, c.te_terms[i].family) << i;
    near(y.te_terms[i].amplitude_rad, c.te_terms[i].amplitude_rad, "amplitude");
    near(y.te_terms[i].phase_rad, c.te_terms[i].phase_rad, "phase");
    near(y.te_terms[i].order_input, c.te_terms[i].order_input, "order_input");
    near(y.te_terms[i].order_output, c.te_terms[i].order_output, "order_output");
  }
  const auto* ys = std::get_if<wavebench::model::ThreeSegmentStiffness>(&y.stiffness.law);
  const auto* cs = std::get_if<wavebench::model::ThreeSegmentStiffness>(&c.stiffness.law);
  ASSERT_TRUE(ys && cs);
  near(ys->k1, cs->k1, "k1");
  near(ys->t1, cs->t1, "t1");
  near(ys->k2, cs->k2, "k2");
  near(ys->t2, cs->t2, "t2");
  near(ys->k3, cs->k3, "k3");
  near(y.backlash.total_rad, c.backlash.total_rad, "backlash");
  near(y.backlash.smoothing_rad, c.backlash.smoothing_rad, "backlash smoothing");
  ASSERT_TRUE(y.damping.damping_ratio && c.damping.damping_ratio);
  near(*y.damping.damping_ratio, *c.damping.damping_ratio, "damping ratio");
  const auto* yf = std::get_if<wavebench::model::CoulombStribeckFriction>(&y.friction);
  const auto* cf = std::get_if<wavebench::model::CoulombStribeckFriction>(&c.friction);
  ASSERT_TRUE(yf && cf);
  near(yf->coulomb, cf->coulomb, "coulomb");
  near(yf->static_torque, cf->static_torque, "static");
  near(yf->stribeck_speed, cf->stribeck_speed, "stribeck");
  near(yf->viscous, cf->viscous, "viscous");
  near(yf->smoothing_speed, cf->smoothing_speed, "smoothing");
  EXPECT_EQ(y.friction_side, c.friction_side);
  near(y.load.output_drag_coulomb, c.load.output_drag_coulomb, "drag");
  near(y.load.drag_smoothing_speed, c.load.drag_smoothing_speed, "drag smoothing");
  EXPECT_EQ(y.stiffness.modulation.size(), c.stiffness.modulation.size());
  EXPECT_EQ(y.stiffness.mean_stiffness.has_value(), c.stiffness.mean_stiffness.has_value());
  EXPECT_TRUE(y.defects.empty() && c.defects.empty());
  using Field = wavebench::model::Sinusoid wavebench::model::LoadParams::*;
  for (const Field s : {&wavebench::model::LoadParams::output_torque,
                        &wavebench::model::LoadParams::drive_ripple}) {
    near((y.load.*s).offset, (c.load.*s).offset, "load offset");
    near((y.load.*s).amplitude, (c.load.*s).amplitude, "load amplitude");
  }
  EXPECT_FALSE(y.load.brake.has_value());
}

}  // namespace
