// The bench over a real SocketCAN vcan0 and Modbus TCP: the simulated devices on their own
// socket and io thread (as `wavebench simbench --clock sync` runs them), the brake controller
// on loopback, the CanopenBench from make_bench() as the daemon uses it. Skips without vcan0.
#include <gtest/gtest.h>

#include <boost/asio/executor_work_guard.hpp>
#include <boost/asio/io_context.hpp>
#include <boost/asio/post.hpp>
#include <future>
#include <thread>

#include "../can/vcan_support.hpp"
#include "bench_test_support.hpp"
#include "wavebench/can/socket_can_bus.hpp"
#include "wavebench/simdevices/brake_server.hpp"
#include "wavebench/simdevices/simulated_bench.hpp"

namespace wavebench::bench {
namespace {

using testing::kRpm;

TEST(VcanBench, DaemonPathAgainstDevicesOnTheirOwnSocket) {
  WAVEBENCH_REQUIRE_VCAN();
  auto config = testing::sim_config();
  const auto true_gear = true_gear_from(config);

  simdevices::BrakeServerOptions brake_options;
  brake_options.endpoint.port = 0;
  brake_options.real_time = false;
  auto brake = simdevices::start_brake_server(brake_options);

  boost::asio::io_context device_io;
  auto work = boost::asio::make_work_guard(device_io);
  can::SocketCanBus device_bus(device_io, ::wavebench::testing::kVcan);
  auto devices_config = simulated_devices_from(config);
  devices_config.gear = true_gear;
  devices_config.clock = simdevices::BenchClock::kSyncDriven;
  simdevices::SimulatedBench devices(devices_config, device_bus);
  auto* server = brake.get();
  devices.set_brake_coupling([server](double omega_out, double dt) {
    server->set_output_speed(omega_out);
    server->step(dt);
    return server->with_controller(
        [](simdevices::PowderBrakeController& c) { return c.physics().torque_capacity(); });
  });
  devices.start();
  std::thread device_thread([&] { device_io.run(); });

  config.can.interface = ::wavebench::testing::kVcan;
  config.simulated.reset();
  config.brake.link.endpoint.port = brake->port();
  {
    auto bench = make_bench(config);
    EXPECT_EQ(simulated_access(*bench), nullptr);
    testing::RecordingObserver observer;
    bench->add_observer(observer);
    bench->connect();
    const double target = bench->latest_sample().theta_in_rad + 2 * M_PI;
    bench->move_input_to(target, 200 * kRpm);
    EXPECT_NEAR(bench->latest_sample().theta_in_rad, target, 2e-3);
    bench->run_input_velocity(100 * kRpm);
    bench->wait_for(1.0);
    EXPECT_NEAR(bench->latest_sample().input_speed_rad_s, 100 * kRpm, 0.02 * 100 * kRpm);
    const auto stats = bench->acquisition_stats();
    EXPECT_GT(stats.samples, 1000U);
    EXPECT_LE(stats.syncs_sent - stats.samples, 1U);
    bench->stop_motion();
    bench->request_stop("vcan test");
    EXPECT_THROW(bench->wait_for(10.0), BenchAborted);
    EXPECT_FALSE(
        brake->with_controller([](simdevices::PowderBrakeController& c) { return c.output_on(); }));
    bench->remove_observer(observer);
  }
  boost::asio::post(device_io, [&] {
    devices.stop();
    work.reset();
    device_io.stop();
  });
  device_thread.join();
  brake->stop();
}

}  // namespace
}  // namespace wavebench::bench
