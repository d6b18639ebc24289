// Input drives (DC motor, servo, kinematic) and loads (drag, powder brake) against steady
// states and closed forms (model.md §2, §7).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "gear_test_support.hpp"
#include "wavebench/model/powder_brake.hpp"
#include "wavebench/model/servo_drive.hpp"

namespace wavebench::model {
namespace {

// Seed 003's table 1.
GearParams seed003(double inductance, Sinusoid voltage) {
  GearParams p = testing::bare_gear(100, 6.8e-4, 2.4e-2, 7.8e5);
  p.viscous_input = 0.003;
  p.viscous_output = 0.005;
  p.damping.coefficient = 0.16;
  p.input = DcMotorInput{6, inductance, 0.52, 0.52, 0.0, voltage};
  return p;
}

TEST(DcMotor, SteadySpeedMatchesClosedFormWithAndWithoutInductance) {
  // K_m (V - K_e w)/R = (C_j + C_z/N^2) w at steady state.
  const double expected = 0.52 * 24 / 6 / (0.52 * 0.52 / 6 + 0.003 + 0.005 / 1e4);
  for (double inductance : {0.0, 2e-3}) {
    // The mesh is lightly damped (zeta = 6e-4): let its start-up ringing die out.
    SimulationOptions o;
    o.t_end = 6;
    o.transient = 6;
    o.sample_rate = 100;
    o.rtol = 1e-9;
    const SimulationResult r = simulate(seed003(inductance, {24, 0, 0, 0}), o);
    ASSERT_EQ(r.response.omega1.size(), 1u);
    EXPECT_NEAR(r.response.omega1[0], expected, 1e-6 * expected) << inductance;
    EXPECT_NEAR(r.response.omega2[0], expected / 100, 1e-6 * expected / 100);
  }
  EXPECT_EQ(GearModel(seed003(0.0, {})).layout().motor_current, -1);
  EXPECT_GE(GearModel(seed003(1e-3, {})).layout().motor_current, 0);
}

TEST(DcMotor, SeedAlternatingSupplyGivesA50HzMotion) {
  SimulationOptions o;
  o.t_end = 0.4;
  o.transient = 0.2;
  o.sample_rate = 5000;
  const SimulationResult r = simulate(seed003(0.0, {0, 24, 50, 0}), o);
  // Zero mean voltage: the speed alternates at 50 Hz about zero.
  int sign_changes = 0;
  for (std::size_t i = 1; i < r.response.omega1.size(); ++i) {
    sign_changes += (r.response.omega1[i] > 0) != (r.response.omega1[i - 1] > 0);
  }
  EXPECT_NEAR(sign_changes, 2 * 50 * 0.2, 2);
}

TEST(ServoDrive, IntegralActionHoldsTheSpeedUnderLoad) {
  GearParams p = testing::bare_gear(50, 1e-3, 0.2, 1e5);
  p.damping.damping_ratio = 0.2;
  p.viscous_input = 1e-3;
  ServoDriveInput s;
  s.velocity_gain = 0.05;
  s.velocity_integral_time = 0.02;
  s.speed_setpoint = 100;
  p.input = s;
  p.load.output_torque.offset = 5;
  SimulationOptions o;
  o.t_end = 2.0;
  o.transient = 2.0;
  o.sample_rate = 10;
  const SimulationResult r = simulate(p, o);
  ASSERT_EQ(r.response.t.size(), 1u);
  EXPECT_NEAR(r.response.omega1[0], 100, 1e-5);
  EXPECT_NEAR(r.response.motor_torque[0], 5.0 / 50 + 1e-3 * 100, 1e-6);

  // A torque limit below what the load needs: the drive saturates and the input decelerates.
  s.torque_limit = 0.05;
  p.input = s;
  p.nominal_input_speed = 100;
  o.t_end = 0.1;
  o.transient = 0.1;
  const SimulationResult limited = simulate(p, o);
  EXPECT_NEAR(limited.response.motor_torque[0], 0.05, 1e-12);
  EXPECT_LT(limited.response.omega1[0], 99);
}

TEST(ServoDrive, PositionLoopReachesTheSetpoint) {
  GearParams p = testing::bare_gear(50, 1e-3, 0.2, 1e5);
  p.damping.damping_ratio = 0.2;
  ServoDriveInput s;
  s.position_control = true;
  s.position_gain = 30;
  s.velocity_gain = 0.05;
  s.velocity_integral_time = 0.02;
  s.speed_limit = 50;
  s.position_setpoint = 10;
  p.input = s;
  SimulationOptions o;
  o.t_end = 2.0;
  o.sample_rate = 100;
  const SimulationResult r = simulate(p, o);
  EXPECT_DOUBLE_EQ(ServoDrive(s).speed_command(0.0), 50);  // the limit caps the command
  EXPECT_NEAR(ServoDrive(s).speed_command(9.9), 30 * 0.1, 1e-12);
  EXPECT_NEAR(r.response.theta1.back(), 10, 1e-4);
}

TEST(KinematicInput, RampAndTraceAreFollowed) {
  GearParams p = testing::bare_gear(50, 1e-3, 0.2, 1e5);
  p.input = KinematicInput{100, 0.5, {}, {}};
  SimulationOptions o;
  o.t_end = 1.0;
  o.sample_rate = 10;
  const SimulationResult r = simulate(p, o);
  EXPECT_NEAR(r.response.theta1[3], 0.5 * 200 * 0.09, 1e-12);
  EXPECT_NEAR(r.response.omega1[3], 200 * 0.3, 1e-12);
  EXPECT_NEAR(r.response.theta1[8], 100 * (0.8 - 0.25), 1e-12);

  KinematicInput trace;
  for (int i = 0; i <= 20; ++i) {
    trace.trace_t.push_back(0.05 * i);
    trace.trace_theta.push_back(3.0 * 0.05 * i + 0.1 * std::sin(0.05 * i));
  }
  p.input = trace;
  const SimulationResult rt = simulate(p, o);
  for (std::size_t i = 0; i < rt.response.t.size(); ++i) {
    const double t = rt.response.t[i];
    EXPECT_NEAR(rt.response.theta1[i], 3 * t + 0.1 * std::sin(t), 1e-12) << t;
  }
}

// k = 20 N*m / 2 A = 10 N*m/A above 0.1 A; the falling curve 0.2 A to the left; no thermal mass.
PowderBrakeParams test_brake() {
  PowderBrakeParams b;
  b.rated_current_a = 2;
  b.rated_torque_nm = 20;
  b.threshold_current_a = 0.1;
  b.hysteresis_a = 0.2;
  b.tau_rise_s = 0.05;
  b.tau_fall_s = 0.08;
  b.heat_capacity_j_per_k = 0;
  return b;
}

TEST(PowderBrake, OneCharacteristicCurvesPlayOperatorAndLag) {
  const PowderBrakeCharacteristic law(test_brake());
  EXPECT_DOUBLE_EQ(law.static_torque(1.0), 10.0);   // T = k I
  EXPECT_DOUBLE_EQ(law.static_torque(0.09), 0.0);   // below the threshold
  EXPECT_DOUBLE_EQ(law.static_torque(0.1), 1.0);    // from the threshold on, k I
  EXPECT_DOUBLE_EQ(law.static_torque(5.0), 20.0);   // saturates at the rated current
  EXPECT_DOUBLE_EQ(law.falling_torque(1.0), 12.0);  // k (I + w)
  // Play operator: up at once, down only past the play width.
  EXPECT_DOUBLE_EQ(law.next_effective_current(0.0, 1.0), 1.0);
  EXPECT_DOUBLE_EQ(law.next_effective_current(1.0, 0.9), 1.0);
  EXPECT_DOUBLE_EQ(law.next_effective_current(1.0, 0.5), 0.7);
  EXPECT_DOUBLE_EQ(law.lag_time_constant(10.0, 2.0), 0.05);
  EXPECT_DOUBLE_EQ(law.lag_time_constant(2.0, 10.0), 0.08);
  EXPECT_DOUBLE_EQ(law.current_for_torque(6.0), 0.6);
  EXPECT_DOUBLE_EQ(law.current_for_torque_from(6.0, 1.0), 0.4);  // falling branch: T/k - w
}

TEST(PowderBrake, CapacityFollowsTheLagToTheStaticCurve) {
  const PowderBrake brake(test_brake(), 1.0);
  EXPECT_DOUBLE_EQ(brake.target_capacity(), 10.0);
  EXPECT_DOUBLE_EQ(brake.capacity_rate(0.0), 10.0 / 0.05);  // rising time constant
  EXPECT_DOUBLE_EQ(brake.capacity_rate(10.0), 0.0);
  EXPECT_NEAR(brake.capacity_rate(12.0), (10.0 - 12.0) / 0.08, 1e-9);  // falling one
  EXPECT_NEAR(brake.torque(9.0, 1.0), 9.0, 1e-9);
  EXPECT_NEAR(brake.torque(9.0, -1.0), -9.0, 1e-9);
  EXPECT_THROW(PowderBrake(test_brake(), -1.0), std::invalid_argument);
  PowderBrakeParams bad = test_brake();
  bad.tau_fall_s = 0;
  EXPECT_THROW(PowderBrake(bad, 1.0), std::invalid_argument);

  // In the model: switched on at t = 0, the brake torque rises as 10 (1 - e^(-t/tau_rise)).
  GearParams p = testing::bare_gear(50, 1e-3, 0.2, 1e5);
  p.damping.damping_ratio = 0.3;
  p.input = KinematicInput{100, 0, {}, {}};
  p.load.brake = test_brake();
  p.load.brake_current_a = 1.0;
  SimulationOptions o;
  o.t_end = 0.2;
  o.sample_rate = 100;
  const SimulationResult r = simulate(p, o);
  for (std::size_t i = 0; i < r.response.t.size(); ++i) {
    const double t = r.response.t[i];
    EXPECT_NEAR(r.response.load_torque[i], 10 * (1 - std::exp(-t / 0.05)), 1e-6) << t;
  }
}

TEST(PowderBrake, HoldsAStoppedOutputAndHeatsWithSlipPower) {
  PowderBrakeParams b = test_brake();
  b.threshold_current_a = 0;
  b.standstill_rad_per_s = 1e-3;
  // Free input, 3 N*m pulling on the output: without the brake (9 N*m at 0.9 A) it would run
  // away.
  GearParams p = testing::bare_gear(50, 1e-3, 0.2, 1e5);
  p.damping.damping_ratio = 0.3;
  p.load.output_torque.offset = -3;
  p.load.brake = b;
  p.load.brake_current_a = 0.9;
  SimulationOptions o;
  o.t_end = 1.0;
  o.transient = 0.5;
  o.sample_rate = 100;
  const SimulationResult held = simulate(p, o);
  for (double w : held.response.omega2) EXPECT_LT(std::abs(w), 1e-3);

  // Slipping at a constant speed heats the mass to ambient + P / G.
  b.heat_capacity_j_per_k = 10;
  b.heat_loss_w_per_k = 2;
  b.ambient_c = 20;
  p.load.brake = b;
  p.load.output_torque.offset = 0;
  p.input = KinematicInput{100, 0, {}, {}};
  const GearModel model(p);
  const StateLayout& L = model.layout();
  std::vector<double> y = model.initial_state();
  const testing::GearRun run = testing::run_gear(model, y, 60, 1, 1e-8, 1e-10);
  const double power = 9 * std::tanh(2 / 1e-3) * 2;  // 9 N*m at omega2 = 100/50
  EXPECT_NEAR(run.y_end[L.brake_temperature], 20 + power / 2, 1e-3);
}

}  // namespace
}  // namespace wavebench::model
