// Safety (bench.md §7) on the in-process simulated bench: heartbeat loss, Modbus link loss,
// over-torque and an operator stop each bring the brake to its safe value (output off,
// setpoint 0, as the simulated controller sees it), quick-stop the servo, make the blocking
// call throw BenchAborted with the reason, and leave the samples up to the trip observed.
#include <gtest/gtest.h>

#include <chrono>
#include <thread>

#include "bench_test_support.hpp"
#include "wavebench/bench/canopen_bench.hpp"
#include "wavebench/simdevices/brake_fault.hpp"

namespace wavebench::bench {
namespace {

using testing::kRpm;
using testing::sim_config;
using testing::SimBench;

// Runs the bench loaded and turning, then waits for the trip; returns its reason.
std::string trip_while_running(SimBench& sim, const std::function<void()>& cause,
                               double brake_nm = 5.0) {
  sim.bench->connect();
  sim.bench->set_brake_torque(brake_nm);
  sim.bench->run_input_velocity(100 * kRpm);
  sim.bench->wait_for(0.3);
  EXPECT_TRUE(sim.brake_output_on());
  EXPECT_FALSE(sim.brake_setpoint_zero());
  cause();
  try {
    sim.bench->wait_for(600.0);
  } catch (const BenchAborted& e) {
    return e.what();
  }
  ADD_FAILURE() << "the bench did not trip";
  return {};
}

void expect_safe_state(SimBench& sim, const std::string& reason) {
  EXPECT_EQ(sim.bench->state(), BenchLifecycle::kFault);
  EXPECT_EQ(sim.bench->fault_reason(), reason);
  EXPECT_FALSE(sim.brake_output_on());
  EXPECT_TRUE(sim.brake_setpoint_zero());
  const auto drive = sim.drive_state();
  EXPECT_TRUE(drive == simdevices::Cia402State::kQuickStopActive ||
              drive == simdevices::Cia402State::kSwitchOnDisabled)
      << simdevices::to_string(drive);
  // Later motion calls throw too, with the same reason.
  try {
    sim.bench->run_input_velocity(10 * kRpm);
    ADD_FAILURE() << "motion allowed in fault";
  } catch (const BenchAborted& e) {
    EXPECT_EQ(std::string(e.what()), reason);
  }
  // The data up to the trip was observed, in order.
  ASSERT_GT(sim.observer.samples.size(), 300U);
  for (std::size_t i = 1; i < sim.observer.samples.size(); ++i)
    ASSERT_GT(sim.observer.samples[i].receive_time_ns, sim.observer.samples[i - 1].receive_time_ns);
}

TEST(BenchSafety, HeartbeatLossTrips) {
  SimBench sim(sim_config());
  const auto reason = trip_while_running(sim, [&] {
    // The encoder stops producing its heartbeat (producer time 0).
    sim.access->devices().encoder().od().set<std::uint16_t>(0x1017, 0, 0);
  });
  EXPECT_NE(reason.find("heartbeat of node 3"), std::string::npos) << reason;
  expect_safe_state(sim, reason);
  // The cause persists: the fault cannot be cleared.
  EXPECT_THROW(sim.bench->clear_fault(), std::runtime_error);
  // Heartbeat back: it can, and the bench moves again.
  sim.access->devices().encoder().od().set<std::uint16_t>(0x1017, 0, 100);
  sim.bench->clear_fault();
  EXPECT_EQ(sim.bench->state(), BenchLifecycle::kInactive);
  sim.bench->move_input_to(sim.bench->latest_sample().theta_in_rad + 1.0, 50 * kRpm);
}

TEST(BenchSafety, NodeLeavingOperationalTrips) {
  // A stopped node sends no PDOs: every cycle waits out its (short) timeout, counted.
  SimBench sim(sim_config([](BenchConfig& c) { c.can.cycle_timeout_s = 0.002; }));
  const auto reason = trip_while_running(sim, [&] {
    auto& bus = dynamic_cast<SimulatedBenchAccess&>(*sim.bench).canopen().master();
    bus.nmt().send(canopen::NmtCommand::stop, 4);
  });
  EXPECT_NE(reason.find("node 4"), std::string::npos) << reason;
  EXPECT_GT(sim.bench->acquisition_stats().cycles_timed_out, 0U);
  EXPECT_GT(sim.bench->acquisition_stats().incomplete_samples, 0U);
  EXPECT_FALSE(sim.observer.samples.back().valid(storage::kTorqueValid));
  expect_safe_state(sim, reason);
}

TEST(BenchSafety, ModbusLinkLossTrips) {
  SimBench sim(sim_config([](BenchConfig& c) {
    c.brake.link.link_loss_timeout = std::chrono::milliseconds(300);
    c.brake.link.response_timeout = std::chrono::milliseconds(100);
    c.brake.link.reconnect_initial_backoff = std::chrono::milliseconds(20);
    c.brake.link.reconnect_max_backoff = std::chrono::milliseconds(50);
  }));
  simdevices::BrakeFault fault;
  fault.kind = simdevices::BrakeFaultKind::dropped_connection;
  const auto reason =
      trip_while_running(sim, [&] { sim.access->brake_server().inject_fault(fault); });
  EXPECT_NE(reason.find("Modbus link"), std::string::npos) << reason;
  EXPECT_EQ(sim.bench->state(), BenchLifecycle::kFault);
  // The link returns: the pending safe state is confirmed when the fault is cleared.
  sim.access->brake_server().clear_fault();
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
  bool cleared = false;
  while (!cleared && std::chrono::steady_clock::now() < deadline) {
    try {
      sim.bench->clear_fault();
      cleared = true;
    } catch (const std::runtime_error&) {
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
  }
  ASSERT_TRUE(cleared);
  EXPECT_FALSE(sim.brake_output_on());
  EXPECT_TRUE(sim.brake_setpoint_zero());
  EXPECT_GT(sim.observer.samples.size(), 300U);
}

TEST(BenchSafety, OverTorqueTrips) {
  SimBench sim(sim_config([](BenchConfig& c) { c.description.limits.max_measured_torque_nm = 8; }));
  const auto reason = trip_while_running(sim, [&] { sim.bench->set_brake_torque(15.0); });
  EXPECT_NE(reason.find("measured torque"), std::string::npos) << reason;
  expect_safe_state(sim, reason);
  // The sample that crossed the limit was observed before the trip.
  EXPECT_GT(std::abs(sim.observer.samples.back().torque_nm), 8.0);
}

TEST(BenchSafety, OperatorStopFromAnotherThreadTrips) {
  SimBench sim(sim_config());
  std::thread stopper;
  const auto reason = trip_while_running(sim, [&] {
    stopper = std::thread([&] {
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
      sim.bench->request_stop("test stop");
    });
  });
  stopper.join();
  EXPECT_EQ(reason, "operator stop: test stop");
  expect_safe_state(sim, reason);
  sim.bench->clear_fault();
  EXPECT_EQ(sim.bench->state(), BenchLifecycle::kInactive);
  EXPECT_EQ(sim.bench->fault_reason(), "");
  sim.bench->run_input_velocity(50 * kRpm);
  sim.bench->wait_for(0.5);
  EXPECT_NEAR(sim.bench->latest_sample().input_speed_rad_s, 50 * kRpm, 0.05 * 50 * kRpm);
}

TEST(BenchSafety, DriveFaultEmcyTrips) {
  SimBench sim(sim_config());
  const auto reason =
      trip_while_running(sim, [&] { sim.access->devices().drive().inject_fault(0x2310); });
  EXPECT_NE(reason.find("EMCY from node 1"), std::string::npos) << reason;
  EXPECT_EQ(sim.bench->state(), BenchLifecycle::kFault);
  EXPECT_FALSE(sim.brake_output_on());
  EXPECT_TRUE(sim.brake_setpoint_zero());
  sim.bench->clear_fault();
  // The reset clears the drive's fault but leaves its power stage off; the next motion
  // enables it.
  EXPECT_EQ(sim.drive_state(), simdevices::Cia402State::kSwitchOnDisabled);
  sim.bench->run_input_velocity(20 * kRpm);
  EXPECT_EQ(sim.drive_state(), simdevices::Cia402State::kOperationEnabled);
}

}  // namespace
}  // namespace wavebench::bench
