// `wavebench simbench`: the simulated bench as its own process on a CAN interface (servo drive,
// output encoder, torque sensor) and optionally the simulated brake controller on a Modbus port.
#include <boost/asio/io_context.hpp>
#include <boost/asio/signal_set.hpp>
#include <boost/asio/steady_timer.hpp>
#include <chrono>
#include <csignal>
#include <iostream>
#include <memory>
#include <optional>
#include <string>

#include "commands.hpp"
#include "wavebench/bench/bench_config.hpp"
#include "wavebench/bench/bench_factory.hpp"
#include "wavebench/can/socket_can_bus.hpp"
#include "wavebench/config/shipped_configs.hpp"
#include "wavebench/config/twin_case.hpp"
#include "wavebench/modbus/modbus_endpoint.hpp"
#include "wavebench/simdevices/brake_server.hpp"
#include "wavebench/simdevices/simulated_bench.hpp"
#include "wavebench/simdevices/simulated_bench_config.hpp"

namespace wavebench::cli {
namespace {

struct SimbenchOptions {
  std::string can_interface = "vcan0";
  std::string modbus;
  std::string config;
  std::string bench_config;
  std::string gear;
  std::string clock;
  std::optional<int> drive_node, encoder_node, torque_node;
  std::optional<double> brake_torque;
  double duration_s = 0;
};

simdevices::SimulatedBenchConfig build_config(const SimbenchOptions& o) {
  simdevices::SimulatedBenchConfig config;
  config.clock = simdevices::BenchClock::kRealTime;
  if (!o.bench_config.empty()) {
    // The same simulated unit as the in-process bench of that config (its true gear, nodes,
    // resolutions, noise), so that runs across processes and in-process can be compared.
    config = bench::simulated_devices_from(bench::load_bench_config(o.bench_config));
    config.clock = simdevices::BenchClock::kRealTime;
  }
  if (!o.config.empty()) config = simdevices::load_simulated_bench_config(o.config, config);
  if (!o.gear.empty()) {
    config.gear = wavebench::config::load_twin_case(o.gear).gear;
  } else if (o.bench_config.empty()) {
    config.gear = wavebench::config::load_twin_case(wavebench::config::shipped_config_dir() /
                                                    "benches" / "simulated-devices-gear.yaml")
                      .gear;
  }
  if (o.clock == "realtime") {
    config.clock = simdevices::BenchClock::kRealTime;
  } else if (o.clock == "sync") {
    config.clock = simdevices::BenchClock::kSyncDriven;
  } else if (!o.clock.empty()) {
    throw std::invalid_argument("--clock '" + o.clock + "' (expected realtime or sync)");
  }
  if (o.drive_node) config.drive.node_id = static_cast<std::uint8_t>(*o.drive_node);
  if (o.encoder_node) config.encoder.node_id = static_cast<std::uint8_t>(*o.encoder_node);
  if (o.torque_node) config.torque_sensor.node_id = static_cast<std::uint8_t>(*o.torque_node);
  if (o.brake_torque) config.brake_torque = *o.brake_torque;
  return config;
}

int run_simbench(const SimbenchOptions& o) {
  simdevices::SimulatedBenchConfig config;
  try {
    config = build_config(o);
  } catch (const std::exception& e) {
    std::cerr << "wavebench simbench: " << e.what() << "\n";
    return 2;
  }
  boost::asio::io_context io;
  can::SocketCanBus bus(io, o.can_interface);
  std::unique_ptr<simdevices::BrakeServer> brake;
  simdevices::SimulatedBench bench(config, bus);
  if (!o.modbus.empty()) {
    simdevices::BrakeServerOptions bo;
    try {
      bo.endpoint = modbus::parse_modbus_endpoint(o.modbus);
    } catch (const std::exception& e) {
      std::cerr << "wavebench simbench: --modbus: " << e.what() << "\n";
      return 2;
    }
    bo.real_time = false;  // the bench's clock steps the brake physics
    brake = simdevices::start_brake_server(bo);
    auto* server = brake.get();
    bench.set_brake_coupling([server](double omega_out, double dt) {
      server->set_output_speed(omega_out);
      server->step(dt);
      return server->with_controller(
          [](simdevices::PowderBrakeController& c) { return c.physics().torque_capacity(); });
    });
  }
  bench.start();
  std::cerr << "wavebench simbench: on " << o.can_interface << ": drive node "
            << int{config.drive.node_id} << ", encoder node " << int{config.encoder.node_id}
            << ", torque sensor node " << int{config.torque_sensor.node_id}
            << (brake ? ", brake on " + o.modbus : std::string()) << "; clock "
            << (config.clock == simdevices::BenchClock::kRealTime ? "real time" : "SYNC-driven")
            << "\n";

  boost::asio::signal_set signals(io, SIGINT, SIGTERM);
  signals.async_wait([&](const boost::system::error_code&, int) { io.stop(); });
  boost::asio::steady_timer deadline(io);
  if (o.duration_s > 0) {
    deadline.expires_after(std::chrono::duration_cast<std::chrono::steady_clock::duration>(
        std::chrono::duration<double>(o.duration_s)));
    deadline.async_wait([&](const boost::system::error_code& ec) {
      if (!ec) io.stop();
    });
  }
  io.run();
  bench.stop();
  if (brake) brake->stop();
  std::cerr << "wavebench simbench: stopped at t = " << bench.now() << " s, " << bench.frames_sent()
            << " frames sent, " << bench.send_errors() << " send errors, " << bench.real_time_slip()
            << " s behind real time (machine too slow)\n";
  return 0;
}

}  // namespace

void register_simbench_commands(CLI::App& app, ExitStatus& status) {
  auto options = std::make_shared<SimbenchOptions>();
  auto* cmd =
      app.add_subcommand("simbench",
                         "Run the simulated bench devices (CiA 402 drive, CiA 406 encoder, torque "
                         "sensor; optionally the Modbus brake) on a CAN interface");
  cmd->add_option("--can", options->can_interface, "SocketCAN interface")->capture_default_str();
  cmd->add_option("--modbus", options->modbus,
                  "also serve the simulated brake controller, e.g. tcp:127.0.0.1:1502");
  cmd->add_option("--config", options->config, "YAML with a simbench: section (node ids, ...)");
  cmd->add_option("--bench-config", options->bench_config,
                  "bench YAML (configs/benches/sim.yaml): serve its simulated unit and devices");
  cmd->add_option("--gear", options->gear,
                  "twin-case YAML whose gear is the bench's true gear (default: the bench "
                  "config's, else configs/benches/simulated-devices-gear.yaml)");
  cmd->add_option("--clock", options->clock, "realtime (default) or sync (one cycle per SYNC)");
  cmd->add_option("--drive-node", options->drive_node, "servo drive node id (default 1)")
      ->check(CLI::Range(1, 127));
  cmd->add_option("--encoder-node", options->encoder_node, "output encoder node id (default 3)")
      ->check(CLI::Range(1, 127));
  cmd->add_option("--torque-node", options->torque_node, "torque sensor node id (default 4)")
      ->check(CLI::Range(1, 127));
  cmd->add_option("--brake-torque", options->brake_torque,
                  "fixed brake torque [N*m] when no --modbus brake runs")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--duration", options->duration_s,
                  "stop after this many seconds (0 = on a signal)")
      ->check(CLI::NonNegativeNumber);
  cmd->callback([options, &status] {
    try {
      status.code = run_simbench(*options);
    } catch (const std::exception& e) {
      std::cerr << "wavebench simbench: " << e.what() << "\n";
      status.code = 1;
    }
  });
}

}  // namespace wavebench::cli
