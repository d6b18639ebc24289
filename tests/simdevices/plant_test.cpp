// The bench plant against closed forms: TE excitation sum, static twist under load through the
// catalogue three-segment stiffness and backlash, brake holding and slipping, dead zone.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "../support/simulated_devices_gear.hpp"
#include "wavebench/simdevices/bench_plant.hpp"

namespace wavebench::simdevices {
namespace {

model::GearParams quiet_gear() {
  model::GearParams p = wavebench::testing::simulated_devices_gear();
  p.te_terms.clear();
  p.friction = model::NoFriction{};
  p.viscous_input = 0;
  p.viscous_output = 0;
  p.load.output_drag_coulomb = 0;
  // model.md §4's size-32 catalogue example, whatever the default unit's own stiffness.
  p.stiffness.law = model::ThreeSegmentStiffness{6.7e4, 29, 1.1e5, 108, 1.2e5};
  return p;
}

TEST(BenchPlant, TeExcitationIsTheSumOfTheTermsOverBothAngles) {
  const model::GearParams p = wavebench::testing::simulated_devices_gear();
  SimulatedBenchPlant plant(p);
  for (const double th1 : {0.0, 1.3, 250.0}) {
    for (const double th2 : {0.0, 0.4, -2.0}) {
      double e = 0;
      for (const auto& t : p.te_terms) {
        e += t.amplitude_rad * std::sin(t.order_input * th1 + t.order_output * th2 + t.phase_rad);
      }
      // The model merges lines into phasors: equal to the sum up to rounding.
      EXPECT_NEAR(plant.te_excitation(th1, th2), e, 1e-12);
    }
  }
}

TEST(BenchPlant, StartsAtRestWithTheMeshUnloadedDespiteATeOffset) {
  // wavebench::testing::simulated_devices_gear() carries a 1.75 arcmin constant TE term: at theta2
  // = 0 the spring would be preloaded by it and the output would ring when the bench starts.
  SimulatedBenchPlant plant(wavebench::testing::simulated_devices_gear());
  EXPECT_NEAR(plant.state().theta_out + plant.te_excitation(0, plant.state().theta_out), 0, 1e-12);
  double peak_speed = 0;
  for (int i = 0; i < 200; ++i) {
    plant.step(1e-3);
    peak_speed = std::max(peak_speed, std::abs(plant.state().omega_out));
    EXPECT_EQ(plant.state().gear_torque, 0.0) << "at step " << i;
  }
  EXPECT_EQ(peak_speed, 0.0);
}

TEST(BenchPlant, CatalogueTwistAtSixtyNewtonMetres) {
  SimulatedBenchPlant plant(quiet_gear());
  const auto& law = std::get<model::ThreeSegmentStiffness>(plant.params().stiffness.law);
  // model.md §4: 60 N*m on the size-32 example twists 7.15e-4 rad.
  const double x = law.t1 / law.k1 + (60 - law.t1) / law.k2;
  EXPECT_NEAR(x, 7.15e-4, 1e-6);
  EXPECT_NEAR(plant.stiffness_torque(x, 0, 0), 60.0, 1e-9);
  EXPECT_NEAR(plant.stiffness_torque(-x, 0, 0), -60.0, 1e-9);
}

TEST(BenchPlant, StaticTwistUnderBalancedLoadSettlesOnTheClosedForm) {
  model::GearParams p = quiet_gear();
  p.load.output_torque.offset = 60;  // resisting the forward direction
  SimulatedBenchPlant plant(p);
  plant.set_motor_torque(60 / plant.ratio());
  plant.step(1.5);
  const auto& law = std::get<model::ThreeSegmentStiffness>(p.stiffness.law);
  const double expected = p.backlash.total_rad / 2 + law.t1 / law.k1 + (60 - law.t1) / law.k2;
  EXPECT_NEAR(plant.state().twist, expected, 2e-8);
  EXPECT_NEAR(plant.state().gear_torque, 60, 1e-3);
  // TE = -twist without excitation.
  EXPECT_NEAR(plant.state().te, -expected, 2e-8);
}

TEST(BenchPlant, NoTorqueInsideTheBacklash) {
  SimulatedBenchPlant plant(quiet_gear());
  const double half = plant.params().backlash.total_rad / 2;
  EXPECT_EQ(plant.backlash_filter(0.99 * half), 0.0);
  EXPECT_EQ(plant.backlash_filter(-0.99 * half), 0.0);
  EXPECT_DOUBLE_EQ(plant.backlash_filter(half + 1e-5), 1e-5);
  EXPECT_DOUBLE_EQ(plant.backlash_filter(-half - 1e-5), -1e-5);
  // A small motor torque turns the input through the dead zone before the output feels it.
  plant.set_motor_torque(1e-4);
  plant.step(1e-3);
  EXPECT_GT(plant.state().omega_in, 0);
  EXPECT_EQ(plant.state().omega_out, 0.0);
  EXPECT_EQ(plant.state().gear_torque, 0.0);
}

TEST(BenchPlant, BrakeHoldsBelowItsSettingAndSlipsAbove) {
  SimulatedBenchPlant plant(quiet_gear());
  plant.set_brake_torque(20);
  plant.set_motor_torque(10 / plant.ratio());  // 10 N*m at the output
  // The input rings against the held output (lightly damped, tau ~ 0.7 s) before it settles.
  plant.step(6.0);
  EXPECT_EQ(plant.state().omega_out, 0.0);
  EXPECT_NEAR(plant.state().gear_torque, 10, 0.05);
  EXPECT_NEAR(plant.state().shaft_torque, 10, 0.05);
  plant.set_motor_torque(30 / plant.ratio());
  plant.step(0.2);
  EXPECT_GT(plant.state().omega_out, 0);
  EXPECT_DOUBLE_EQ(plant.state().shaft_torque, 20);
}

TEST(BenchPlant, RejectsUnusableParametersNamingThem) {
  model::GearParams p = wavebench::testing::simulated_devices_gear();
  p.inertia_output = 0;
  try {
    SimulatedBenchPlant plant(p);
    FAIL() << "accepted zero inertia";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("inertia_output"), std::string::npos);
  }
  p = wavebench::testing::simulated_devices_gear();
  p.geometry.ratio = 0;
  p.geometry.z_circ = p.geometry.z_flex;
  EXPECT_THROW(SimulatedBenchPlant{p}, std::invalid_argument);
}

}  // namespace
}  // namespace wavebench::simdevices
