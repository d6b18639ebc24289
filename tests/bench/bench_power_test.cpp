// The servo is powered only while a run needs it (issue #9), on the in-process simulated bench:
// connected means inactive (everything readable, drive and brake output off), the first motion
// enables the drive, deactivate() and a trip switch it off, a reset does not switch it on, and
// disconnect() is a clean exit (brake off, its watchdog register back to 0, drive switch-on
// disabled, nodes pre-operational).
#include <gtest/gtest.h>

#include "bench_test_support.hpp"
#include "wavebench/bench/canopen_bench.hpp"

namespace wavebench::bench {
namespace {

using simdevices::Cia402State;
using testing::kRpm;
using testing::sim_config;
using testing::SimBench;

bool powered_off(Cia402State s) {
  return s == Cia402State::kSwitchOnDisabled || s == Cia402State::kReadyToSwitchOn;
}

std::uint16_t brake_watchdog_register(SimBench& sim) {
  return sim.access->brake_server().with_controller(
      [](simdevices::PowderBrakeController& c) { return c.holding()[1]; });
}

TEST(BenchPower, ConnectedBenchIsInactiveAndStillReadsEveryChannel) {
  SimBench sim(sim_config());
  sim.bench->connect();
  ASSERT_EQ(sim.bench->state(), BenchLifecycle::kInactive);
  EXPECT_TRUE(powered_off(sim.drive_state())) << simdevices::to_string(sim.drive_state());
  EXPECT_FALSE(sim.brake_output_on());
  const auto before = sim.observer.samples.size();
  sim.bench->idle_for(0.2);
  ASSERT_GT(sim.observer.samples.size(), before + 100);
  const auto& s = sim.observer.samples.back();
  EXPECT_TRUE(s.valid(storage::kThetaInValid));
  EXPECT_TRUE(s.valid(storage::kThetaOutValid));
  EXPECT_TRUE(s.valid(storage::kTorqueValid));
  // The drive's statusword comes with every cycle and says the power stage is off.
  auto& canopen = sim.access->canopen();
  ASSERT_TRUE(canopen.latest_drive().status_valid);
  const auto state = canopen::decode_state(canopen.latest_drive().statusword);
  EXPECT_TRUE(state == canopen::Cia402State::switch_on_disabled ||
              state == canopen::Cia402State::ready_to_switch_on)
      << canopen::to_string(state);
  EXPECT_TRUE(powered_off(sim.drive_state()));
}

TEST(BenchPower, FirstMotionEnablesAndDeactivateSwitchesDriveAndBrakeOff) {
  SimBench sim(sim_config());
  sim.bench->connect();
  // A zero brake torque while inactive is a setpoint only: the output stays off.
  sim.bench->set_brake_torque(0.0);
  sim.bench->wait_for(0.1);
  EXPECT_EQ(sim.bench->state(), BenchLifecycle::kInactive);
  EXPECT_FALSE(sim.brake_output_on());
  EXPECT_TRUE(powered_off(sim.drive_state()));

  sim.bench->set_brake_torque(2.0);
  EXPECT_EQ(sim.bench->state(), BenchLifecycle::kActive);
  sim.bench->move_input_to(sim.bench->latest_sample().theta_in_rad + 2.0, 100 * kRpm);
  EXPECT_EQ(sim.drive_state(), Cia402State::kOperationEnabled);
  EXPECT_EQ(sim.bench->state(), BenchLifecycle::kActive);
  sim.bench->wait_for(0.1);
  EXPECT_TRUE(sim.brake_output_on());

  sim.bench->deactivate();
  EXPECT_EQ(sim.drive_state(), Cia402State::kReadyToSwitchOn);
  EXPECT_FALSE(sim.brake_output_on());
  EXPECT_TRUE(sim.brake_setpoint_zero());
  EXPECT_EQ(sim.bench->state(), BenchLifecycle::kInactive);
  // Still acquiring while inactive.
  const auto samples = sim.bench->acquisition_stats().samples;
  sim.bench->idle_for(0.1);
  EXPECT_GT(sim.bench->acquisition_stats().samples, samples + 50);

  // A velocity run after it enables again, and stops.
  sim.bench->run_input_velocity(30 * kRpm);
  EXPECT_EQ(sim.drive_state(), Cia402State::kOperationEnabled);
  sim.bench->wait_for(0.3);
  EXPECT_NEAR(sim.bench->latest_sample().input_speed_rad_s, 30 * kRpm, 0.1 * 30 * kRpm);
  sim.bench->stop_motion();
  sim.bench->deactivate();
  EXPECT_EQ(sim.drive_state(), Cia402State::kReadyToSwitchOn);
}

TEST(BenchPower, AFaultKeepsTheSafeStateAndTheResetDoesNotEnable) {
  SimBench sim(sim_config());
  sim.bench->connect();
  sim.bench->set_brake_torque(2.0);
  sim.bench->run_input_velocity(60 * kRpm);
  sim.bench->wait_for(0.2);
  sim.bench->request_stop("test");
  EXPECT_THROW(sim.bench->wait_for(10.0), BenchAborted);
  // What the run executor does when a run ends aborted.
  sim.bench->deactivate();
  EXPECT_EQ(sim.bench->state(), BenchLifecycle::kFault);
  EXPECT_EQ(sim.drive_state(), Cia402State::kSwitchOnDisabled);
  EXPECT_FALSE(sim.brake_output_on());
  sim.bench->idle_for(0.3);
  EXPECT_EQ(sim.drive_state(), Cia402State::kSwitchOnDisabled);

  sim.bench->clear_fault();
  EXPECT_EQ(sim.bench->state(), BenchLifecycle::kInactive);
  EXPECT_TRUE(powered_off(sim.drive_state())) << simdevices::to_string(sim.drive_state());
  EXPECT_FALSE(sim.brake_output_on());
  sim.bench->move_input_to(sim.bench->latest_sample().theta_in_rad + 1.0, 50 * kRpm);
  EXPECT_EQ(sim.drive_state(), Cia402State::kOperationEnabled);
}

TEST(BenchPower, DisconnectIsACleanExit) {
  SimBench sim(sim_config());
  sim.bench->connect();
  sim.bench->set_brake_torque(2.0);
  sim.bench->run_input_velocity(30 * kRpm);
  sim.bench->wait_for(0.2);
  ASSERT_TRUE(sim.brake_output_on());
  ASSERT_EQ(sim.drive_state(), Cia402State::kOperationEnabled);
  ASSERT_EQ(brake_watchdog_register(sim), 500);  // brake-default.yaml, armed by the supervisor
  auto& devices = sim.access->devices();
  ASSERT_EQ(devices.drive().nmt_state(), simdevices::NmtState::kOperational);

  sim.bench->disconnect();
  EXPECT_EQ(sim.bench->state(), BenchLifecycle::kUnconfigured);
  EXPECT_FALSE(sim.brake_output_on());
  EXPECT_TRUE(sim.brake_setpoint_zero());
  EXPECT_EQ(brake_watchdog_register(sim), 0);
  EXPECT_EQ(sim.drive_state(), Cia402State::kSwitchOnDisabled);
  EXPECT_EQ(devices.drive().nmt_state(), simdevices::NmtState::kPreOperational);
  EXPECT_EQ(devices.encoder().nmt_state(), simdevices::NmtState::kPreOperational);
  EXPECT_EQ(devices.torque_sensor().nmt_state(), simdevices::NmtState::kPreOperational);

  // And the bench connects again from there, inactive.
  sim.bench->connect();
  EXPECT_EQ(sim.bench->state(), BenchLifecycle::kInactive);
  EXPECT_TRUE(powered_off(sim.drive_state()));
  EXPECT_EQ(devices.drive().nmt_state(), simdevices::NmtState::kOperational);
}

}  // namespace
}  // namespace wavebench::bench
