#include "wavebench/simdevices/powder_brake_physics.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace wavebench::simdevices {
namespace {

// Defaults: 100 N·m at 2 A (k = 50 N·m/A), threshold 0.05 A, play 0.04 A, tau 0.08 / 0.15 s.
constexpr double k = 50.0;

void settle(PowderBrakePhysics& b) {
  b.step(60.0);
}  // 60 s ≫ τ: exp(-400) vanishes

TEST(PowderBrakePhysics, TorqueProportionalToCurrentWithinRatedRange) {
  for (const double amps : {0.1, 0.25, 0.5, 1.0, 1.5, 2.0}) {
    PowderBrakePhysics b;
    b.set_coil_current(amps);
    settle(b);
    EXPECT_NEAR(b.torque_capacity() / amps, k, 1e-9) << amps << " A";
  }
}

TEST(PowderBrakePhysics, NoTorqueBelowThresholdAndSaturatedAboveRated) {
  PowderBrakePhysics b;
  b.set_coil_current(0.04);
  settle(b);
  EXPECT_EQ(b.torque_capacity(), 0.0);
  b.set_coil_current(3.0);
  settle(b);
  EXPECT_NEAR(b.torque_capacity(), 100.0, 1e-9);
}

TEST(PowderBrakePhysics, FirstOrderLagWithRisingTimeConstant) {
  PowderBrakePhysics b;
  b.set_coil_current(1.0);
  // Many small steps must compose to the closed form T(t) = T_ss (1 - exp(-t/τ)).
  for (int i = 0; i < 80; ++i) b.step(0.001);
  EXPECT_NEAR(b.torque_capacity(), 50.0 * (1.0 - std::exp(-1.0)), 1e-9);
  for (int i = 0; i < 80; ++i) b.step(0.001);
  EXPECT_NEAR(b.torque_capacity(), 50.0 * (1.0 - std::exp(-2.0)), 1e-9);
}

TEST(PowderBrakePhysics, FallingCurveIsHigherAndSlower) {
  PowderBrakePhysics rising;
  rising.set_coil_current(0.5);
  settle(rising);

  PowderBrakePhysics falling;
  falling.set_coil_current(1.0);
  settle(falling);
  falling.set_coil_current(0.5);
  // Play operator: I_eff = 0.5 + 0.04 on the falling branch.
  const double t_ss = k * 0.54;
  const double t0 = falling.torque_capacity();
  falling.step(0.15);  // τ_fall
  EXPECT_NEAR(falling.torque_capacity(), t_ss + (t0 - t_ss) * std::exp(-1.0), 1e-9);
  settle(falling);
  EXPECT_NEAR(falling.torque_capacity(), t_ss, 1e-9);
  EXPECT_NEAR(rising.torque_capacity(), k * 0.5, 1e-9);
  EXPECT_GT(falling.torque_capacity(), rising.torque_capacity());

  // A small dip inside the play width leaves the torque where it was.
  PowderBrakePhysics dip;
  dip.set_coil_current(1.0);
  settle(dip);
  dip.set_coil_current(0.97);
  settle(dip);
  EXPECT_NEAR(dip.torque_capacity(), 50.0, 1e-9);
  // Rising again from the falling branch follows the rising curve once past I_eff.
  falling.set_coil_current(0.8);
  settle(falling);
  EXPECT_NEAR(falling.torque_capacity(), k * 0.8, 1e-9);
}

TEST(PowderBrakePhysics, HoldsUpToCapacityWhenStoppedAndSlipsWhenTurning) {
  PowderBrakePhysics b;
  b.set_coil_current(1.0);
  settle(b);
  b.set_output_speed(0.0);
  EXPECT_TRUE(b.stopped());
  EXPECT_NEAR(b.shaft_torque(30.0), -30.0, 1e-12);
  EXPECT_NEAR(b.shaft_torque(-20.0), 20.0, 1e-12);
  EXPECT_NEAR(b.shaft_torque(80.0), -50.0, 1e-9);
  EXPECT_EQ(b.slip_power(), 0.0);
  b.set_output_speed(2.0);
  EXPECT_NEAR(b.shaft_torque(0.0), -50.0, 1e-9);
  EXPECT_NEAR(b.slip_power(), 100.0, 1e-7);
  b.set_output_speed(-2.0);
  EXPECT_NEAR(b.shaft_torque(0.0), 50.0, 1e-9);
  EXPECT_NEAR(b.slip_power(), 100.0, 1e-7);
}

TEST(PowderBrakePhysics, SlipPowerHeatsLumpedThermalMass) {
  model::PowderBrakeParams p;
  PowderBrakePhysics b(p);
  b.set_coil_current(1.0);
  settle(b);  // at standstill: no heating
  EXPECT_NEAR(b.temperature(), p.ambient_c, 1e-12);
  b.set_output_speed(2.0);  // 50 N·m · 2 rad/s = 100 W
  const double power = b.slip_power();
  for (int i = 0; i < 100; ++i) b.step(1.0);
  const double g = p.heat_loss_w_per_k;
  const double c = p.heat_capacity_j_per_k;
  EXPECT_NEAR(b.temperature(), p.ambient_c + power / g * (1.0 - std::exp(-g * 100.0 / c)), 1e-6);
  // More slip power, faster heating.
  PowderBrakePhysics hot(p);
  hot.set_coil_current(2.0);
  settle(hot);
  hot.set_output_speed(2.0);
  for (int i = 0; i < 100; ++i) hot.step(1.0);
  EXPECT_GT(hot.temperature(), b.temperature());
}

TEST(PowderBrakePhysics, OpenCoilLosesTorque) {
  PowderBrakePhysics b;
  b.set_coil_current(1.0);
  settle(b);
  b.set_coil_open(true);
  EXPECT_EQ(b.coil_current(), 0.0);
  settle(b);
  EXPECT_NEAR(b.torque_capacity(), 0.0, 1e-9);
}

}  // namespace
}  // namespace wavebench::simdevices

namespace wavebench::simdevices {
namespace {

TEST(PowderBrakePhysics, TorqueInverseFromEitherBranch) {
  PowderBrakePhysics b;
  b.set_coil_current(b.current_for_torque_from_here(60.0));
  settle(b);
  EXPECT_NEAR(b.torque_capacity(), 60.0, 1e-9);
  // Coming down, the falling branch's inverse lands on the target instead of 2 N·m above.
  b.set_coil_current(b.current_for_torque_from_here(40.0));
  settle(b);
  EXPECT_NEAR(b.torque_capacity(), 40.0, 1e-9);
  EXPECT_NEAR(b.coil_current(), 0.8 - 0.04, 1e-12);
  b.set_coil_current(b.current_for_torque(40.0));  // plain rising inverse: no change of state
  settle(b);
  EXPECT_NEAR(b.torque_capacity(), 40.0, 1e-9);
}

}  // namespace
}  // namespace wavebench::simdevices
