// The in-process simulated bench through the daemon's code path (CANopen master on a virtual
// bus, Modbus TCP to the simulated brake controller), on the simulated clock.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>

#include "bench_test_support.hpp"
#include "wavebench/bench/canopen_bench.hpp"
#include "wavebench/simdevices/bench_plant.hpp"

namespace wavebench::bench {
namespace {

using testing::kRpm;
using testing::sim_config;
using testing::SimBench;

TEST(SimulatedBench, ConnectsAndAProfilePositionMoveLands) {
  SimBench sim(sim_config());
  ASSERT_NE(sim.access, nullptr);
  EXPECT_EQ(sim.bench->state(), BenchLifecycle::kUnconfigured);
  sim.bench->connect();
  ASSERT_EQ(sim.bench->state(), BenchLifecycle::kInactive);
  // Inactive until the first motion command (bench_power_test.cpp).
  EXPECT_EQ(sim.drive_state(), simdevices::Cia402State::kSwitchOnDisabled);
  // The twin's gear is the nominal case, the simulated unit's is varied from it.
  EXPECT_NE(sim.access->true_gear().backlash.total_rad,
            sim.bench->description().twin_gear.backlash.total_rad);

  const double theta0 = sim.bench->latest_sample().theta_in_rad;
  const double target = theta0 + 5 * 2 * M_PI;  // five input turns
  sim.bench->move_input_to(target, 300 * kRpm);
  EXPECT_EQ(sim.drive_state(), simdevices::Cia402State::kOperationEnabled);
  const auto& s = sim.bench->latest_sample();
  ASSERT_TRUE(s.valid(storage::kThetaInValid));
  EXPECT_NEAR(s.theta_in_rad, target, 2e-3);  // within the drive's position window
  // The output followed through the gear: 5/100 turn, give or take TE and backlash.
  ASSERT_TRUE(s.valid(storage::kThetaOutValid));
  EXPECT_NEAR(s.theta_out_rad - sim.observer.samples.front().theta_out_rad, 5 * 2 * M_PI / 100,
              5e-3);
  // The plant agrees with what the bench measured (truth vs measurement).
  EXPECT_NEAR(sim.access->devices().plant().state().theta_in, s.theta_in_rad, 1e-3);

  EXPECT_THROW(sim.bench->move_input_to(0, -1), std::invalid_argument);
  EXPECT_THROW(sim.bench->move_input_to(0, 1e6), std::invalid_argument);
  EXPECT_EQ(sim.bench->state(), BenchLifecycle::kActive);
  sim.bench->disconnect();
  EXPECT_EQ(sim.bench->state(), BenchLifecycle::kUnconfigured);
  EXPECT_FALSE(sim.brake_output_on());
}

TEST(SimulatedBench, ProfileVelocityAt100RpmGivesThatSpeed) {
  SimBench sim(sim_config());
  sim.bench->connect();
  sim.bench->run_input_velocity(100 * kRpm);
  sim.bench->wait_for(1.0);  // run-in
  const std::size_t from = sim.observer.samples.size();
  const double t0 = sim.bench->now();
  sim.bench->wait_for(1.0);
  const auto& a = sim.observer.samples[from];
  const auto& b = sim.observer.samples.back();
  const double dt = (b.receive_time_ns - a.receive_time_ns) * 1e-9;
  ASSERT_GT(dt, 0.9);
  EXPECT_NEAR((b.theta_in_rad - a.theta_in_rad) / dt, 100 * kRpm, 0.005 * 100 * kRpm);
  EXPECT_NEAR(b.input_speed_rad_s, 100 * kRpm, 0.02 * 100 * kRpm);
  // Output at 1/100 of the input speed, in the bench's direction.
  EXPECT_NEAR((b.theta_out_rad - a.theta_out_rad) / dt, 1 * kRpm, 0.02 * kRpm);
  EXPECT_NEAR(sim.bench->now() - t0, 1.0, 2e-3);
  sim.bench->stop_motion();
  EXPECT_LT(std::abs(sim.bench->latest_sample().input_speed_rad_s), 0.05);
}

TEST(SimulatedBench, OneSamplePerSyncAndBenchTimeIsSyncIndexTimesPeriod) {
  SimBench sim(sim_config());
  sim.bench->connect();
  sim.bench->set_brake_torque(2.0);
  sim.bench->run_input_velocity(60 * kRpm);
  const auto before = sim.bench->acquisition_stats();
  const double t_before = sim.bench->now();
  const auto real_before = std::chrono::steady_clock::now();
  const std::size_t n_before = sim.observer.samples.size();
  sim.bench->wait_for(2.0);
  const double real =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - real_before).count();
  const auto after = sim.bench->acquisition_stats();
  const auto syncs = after.syncs_sent - before.syncs_sent;
  const auto samples = after.samples - before.samples;
  EXPECT_GE(syncs, 2000U);
  // Every SYNC but the one still open has its sample; bench time is N x period exactly.
  EXPECT_LE(syncs - samples, 1U);
  EXPECT_EQ(sim.observer.samples.size() - n_before, samples);
  EXPECT_NEAR(sim.bench->now() - t_before, static_cast<double>(syncs) * 1e-3, 1e-9);
  EXPECT_EQ(after.cycles_timed_out, 0U);
  // Consecutive samples: SYNC counters 1..240 in order, receive times one period apart.
  std::size_t can_complete = 0, brake_valid = 0;
  for (std::size_t i = n_before + 1; i < sim.observer.samples.size(); ++i) {
    const auto& p = sim.observer.samples[i - 1];
    const auto& s = sim.observer.samples[i];
    EXPECT_EQ(s.sync_counter, p.sync_counter % 240 + 1);
    EXPECT_EQ(s.receive_time_ns - p.receive_time_ns, 1000000);
    const auto can = storage::kThetaInValid | storage::kThetaOutValid | storage::kInputSpeedValid |
                     storage::kTorqueValid;
    if ((s.flags & can) == can) ++can_complete;
    if (s.valid(storage::kBrakeTorqueValid)) ++brake_valid;
  }
  EXPECT_EQ(can_complete, samples - 1);
  EXPECT_GT(brake_valid, 0U);
  EXPECT_GT(after.bus_load, 0.3);
  EXPECT_LT(after.bus_load, 0.8);
  // Loosely: the simulated clock is not slower than the bench time it covers.
  RecordProperty("bench_to_real_ratio", std::to_string(2.0 / real));
  std::printf("simulated clock: 2.0 s of bench time in %.3f s real (x%.1f)\n", real, 2.0 / real);
}

TEST(SimulatedBench, BrakeTorqueReachesTheShaftAndTheReadback) {
  SimBench sim(sim_config());
  sim.bench->connect();
  sim.bench->run_input_velocity(100 * kRpm);
  sim.bench->set_brake_torque(20.0, 0);
  sim.bench->wait_for(2.0);
  // The brake opposes motion: the shaft torque the sensor reads is near the set torque.
  double sum = 0;
  int n = 0;
  for (std::size_t i = sim.observer.samples.size() - 200; i < sim.observer.samples.size(); ++i) {
    sum += sim.observer.samples[i].torque_nm;
    ++n;
  }
  EXPECT_NEAR(std::abs(sum / n), 20.0, 2.0);
  EXPECT_TRUE(sim.brake_output_on());
  EXPECT_THROW(sim.bench->set_brake_torque(-1), std::invalid_argument);
  EXPECT_THROW(sim.bench->set_brake_torque(500), std::invalid_argument);
  sim.bench->set_brake_torque(0);
  sim.bench->stop_motion();
}

TEST(SimulatedBench, RealClockRunsInProcessToo) {
  SimBench sim(sim_config([](BenchConfig& c) {
    c.clock = BenchClockKind::kReal;
    c.description.simulated_clock = false;
  }));
  sim.bench->connect();
  std::vector<double> lateness;
  dynamic_cast<SimulatedBenchAccess&>(*sim.bench)
      .canopen()
      .on_sync_tick([&](const canopen::SyncProducer::Tick& t) {
        lateness.push_back(std::chrono::duration<double>(t.sent - t.deadline).count());
      });
  sim.bench->run_input_velocity(100 * kRpm);
  sim.bench->wait_for(0.3);
  const auto stats = sim.bench->acquisition_stats();
  EXPECT_GT(stats.samples, 50U);
  EXPECT_GE(stats.syncs_sent + 1, stats.samples);
  EXPECT_FALSE(lateness.empty());
  EXPECT_GE(stats.sync_lateness_max_s, stats.sync_lateness_p50_s);
  EXPECT_GT(stats.real_time_s, 0.3);
  EXPECT_NEAR(stats.bench_time_s, stats.real_time_s, 0.05);
  sim.bench->stop_motion();
}

}  // namespace
}  // namespace wavebench::bench

namespace wavebench::bench {
namespace {

// TE from the bench's samples (θ_in and θ_out of the same SYNC, the sense applied in one place)
// equals the simulated plant's own TE at standstill, for either output direction.
void expect_measured_te_is_the_plants(int direction_sign) {
  SimBench sim(
      sim_config([&](BenchConfig& c) { c.description.sense.direction_sign = direction_sign; }));
  sim.bench->connect();
  const auto sense = sim.bench->description().sense;
  for (const double output_turns : {0.13, 0.41}) {
    sim.bench->move_input_to(output_turns * 2 * M_PI * sense.ratio, 600 * kRpm);
    sim.bench->wait_for(0.3);
    const std::size_t from = sim.observer.samples.size();
    sim.bench->wait_for(0.3);
    double te = 0;
    for (std::size_t i = from; i < sim.observer.samples.size(); ++i) {
      const auto& s = sim.observer.samples[i];
      ASSERT_TRUE(s.valid(storage::kThetaInValid) && s.valid(storage::kThetaOutValid));
      te += sense.transmission_error(s.theta_in_rad, s.theta_out_rad);
    }
    te /= static_cast<double>(sim.observer.samples.size() - from);
    const double truth = sim.access->devices().plant().state().te;
    // Encoder noise 0.5 arcsec averaged over 300 samples, input quantisation 0.1 arcsec.
    EXPECT_NEAR(te, truth, 0.5 / 3600 * M_PI / 180) << "direction " << direction_sign;
    EXPECT_GT(std::abs(truth), 1e-5);  // a TE worth measuring (arcmin-sized)
  }
}

TEST(SimulatedBench, MeasuredTeIsThePlantsTe) {
  expect_measured_te_is_the_plants(1);
}
TEST(SimulatedBench, MeasuredTeIsThePlantsTeWithTheOutputReversed) {
  expect_measured_te_is_the_plants(-1);
}

}  // namespace
}  // namespace wavebench::bench
