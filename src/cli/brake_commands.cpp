// `wavebench brake ...`: commissioning of the powder-brake controller over Modbus, and
// `wavebench sim-brake`: the simulated controller as its own process.
#include <chrono>
#include <csignal>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <thread>

#include "commands.hpp"
#include "wavebench/modbus/brake_client.hpp"
#include "wavebench/modbus/brake_config.hpp"
#include "wavebench/modbus/modbus_error.hpp"
#include "wavebench/simdevices/brake_server.hpp"
#include "wavebench/simdevices/pty_pair.hpp"

namespace wavebench::cli {

namespace {

namespace mb = wavebench::modbus;

struct BrakeOptions {
  std::string modbus;
  std::string config;
  int unit = -1;
  int timeout_ms = -1;
  double value = 0.0;
  double ramp = 0.0;
  bool torque = false;
  bool json = false;
  double duration_s = 0.0;
  std::string secret;  // the simulated controller's unlock secret (brake_registers::unlock)
};

template <typename Body>
void run(ExitStatus& status, Body&& body) {
  try {
    body();
    status.code = 0;
  } catch (const mb::BrakeConfigError& e) {
    std::cerr << "wavebench brake: " << e.what() << "\n";
    status.code = 2;
  } catch (const std::invalid_argument& e) {
    std::cerr << "wavebench brake: " << e.what() << "\n";
    status.code = 2;
  } catch (const mb::ModbusError& e) {
    std::cerr << "wavebench brake: " << e.what() << "\n";
    if (e.kind() == mb::ModbusErrorKind::exception && e.exception_code() == 1) {
      // What a locked simulated controller answers (brake_registers::unlock).
      std::cerr << "wavebench brake: the controller refused the write: a simulated controller "
                   "takes writes only after its unlock secret (--secret); the daemon's own "
                   "brake takes none but the daemon's\n";
    }
    status.code = 1;
  } catch (const std::exception& e) {
    std::cerr << "wavebench brake: " << e.what() << "\n";
    status.code = 1;
  }
}

mb::BrakeClientConfig client_config(const BrakeOptions& o) {
  mb::BrakeClientConfig cfg;
  if (!o.config.empty()) cfg = mb::load_brake_config_file(o.config);
  if (!o.modbus.empty()) cfg.link.endpoint = mb::parse_modbus_endpoint(o.modbus);
  if (o.unit >= 0) cfg.link.unit_id = o.unit;
  if (o.timeout_ms > 0) cfg.link.response_timeout = std::chrono::milliseconds(o.timeout_ms);
  if (!o.secret.empty()) cfg.link.unlock_secret = simdevices::parse_unlock_secret(o.secret);
  return cfg;
}

void print_readback(const mb::BrakeReadback& r, bool json) {
  if (json) {
    nlohmann::json j{{"output_on", r.status.output_on},
                     {"alarm", r.status.alarm},
                     {"over_temperature", r.status.over_temperature},
                     {"watchdog_tripped", r.status.watchdog_tripped},
                     {"coil_open", r.status.coil_open},
                     {"at_setpoint", r.status.at_setpoint},
                     {"status_word", r.status.raw},
                     {"coil_current_a", r.coil_current_a},
                     {"torque_nm", r.torque_nm},
                     {"temperature_c", r.temperature_c},
                     {"slip_power_w", r.slip_power_w},
                     {"alarm_code", r.alarm_code},
                     {"alarm_text", r.alarm_text}};
    std::cout << j.dump(2) << "\n";
    return;
  }
  std::cout << "status        " << mb::describe_status(r.status) << " (0x" << std::hex
            << r.status.raw << std::dec << ")\n"
            << "coil current  " << r.coil_current_a << " A\n"
            << "torque        " << r.torque_nm << " N·m\n"
            << "temperature   " << r.temperature_c << " °C\n"
            << "slip power    " << r.slip_power_w << " W\n"
            << "alarms        " << r.alarm_text << "\n";
}

void add_link_options(CLI::App* cmd, BrakeOptions& o) {
  cmd->add_option("--modbus", o.modbus, "tcp:HOST:PORT or rtu:DEVICE[:BAUD[:PARITY...]]");
  cmd->add_option("--config", o.config, "brake YAML config (default: built-in map)");
  cmd->add_option("--unit", o.unit, "Modbus unit id")->check(CLI::Range(0, 255));
  cmd->add_option("--timeout-ms", o.timeout_ms, "response timeout")->check(CLI::Range(1, 60000));
  cmd->add_option("--secret", o.secret,
                  "unlock secret of a simulated controller started with one (hex)");
}

volatile std::sig_atomic_t g_stop = 0;
extern "C" void on_stop_signal(int) {
  g_stop = 1;
}

void run_sim_brake(const BrakeOptions& o) {
  simdevices::BrakeServerOptions so;
  std::unique_ptr<simdevices::PtyPair> pty;
  if (o.modbus == "rtu:pty") {
    pty = std::make_unique<simdevices::PtyPair>();
    so.endpoint = mb::parse_modbus_endpoint("rtu:" + pty->slave_path());
    so.rtu_fd = pty->release_master();
  } else {
    so.endpoint = mb::parse_modbus_endpoint(o.modbus.empty() ? "tcp:127.0.0.1:1502" : o.modbus);
  }
  if (o.unit >= 0) so.unit_id = o.unit;
  // Locked by default: anyone on the machine can reach a loopback port.
  if (o.secret.empty() || o.secret == "random") {
    so.unlock_secret = simdevices::random_unlock_secret();
  } else if (o.secret != "none") {
    so.unlock_secret = simdevices::parse_unlock_secret(o.secret);
  }
  auto server = simdevices::start_brake_server(so);
  if (so.unlock_secret && (o.secret.empty() || o.secret == "random")) {
    std::cout << "unlock secret " << simdevices::unlock_secret_text(*so.unlock_secret) << "\n";
  }
  if (so.endpoint.transport == mb::Transport::tcp) {
    std::cout << "simulated brake controller on tcp:" << so.endpoint.host << ":" << server->port()
              << " unit " << so.unit_id << "\n";
  } else {
    std::cout << "simulated brake controller on rtu:" << so.endpoint.device << " unit "
              << so.unit_id << "\n";
  }
  std::cout.flush();
  std::signal(SIGINT, on_stop_signal);
  std::signal(SIGTERM, on_stop_signal);
  const auto end = std::chrono::steady_clock::now() +
                   std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                       std::chrono::duration<double>(o.duration_s));
  while (!g_stop && (o.duration_s <= 0.0 || std::chrono::steady_clock::now() < end)) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  server->stop();
  std::cout << "served " << server->requests() << " requests\n";
}

}  // namespace

void register_brake_commands(CLI::App& app, ExitStatus& status) {
  auto opts = std::make_shared<BrakeOptions>();
  auto* brake = app.add_subcommand("brake", "powder-brake controller over Modbus");
  brake->require_subcommand(1);

  auto* st = brake->add_subcommand("status", "read status, current, torque, temperature, alarms");
  add_link_options(st, *opts);
  st->add_flag("--json", opts->json, "print JSON");
  st->callback([opts, &status] {
    run(status, [&] {
      mb::BrakeClient client(client_config(*opts));
      client.connect();
      print_readback(client.read(), opts->json);
    });
  });

  auto* en = brake->add_subcommand("enable", "switch the brake output on");
  add_link_options(en, *opts);
  en->callback([opts, &status] {
    run(status, [&] {
      mb::BrakeClient client(client_config(*opts));
      client.connect();
      client.enable();
      print_readback(client.read(), false);
    });
  });

  auto* dis = brake->add_subcommand("disable", "switch the brake output off");
  add_link_options(dis, *opts);
  dis->callback([opts, &status] {
    run(status, [&] {
      mb::BrakeClient client(client_config(*opts));
      client.connect();
      client.disable();
      print_readback(client.read(), false);
    });
  });

  auto* reset = brake->add_subcommand("reset", "reset latched alarms");
  add_link_options(reset, *opts);
  reset->callback([opts, &status] {
    run(status, [&] {
      mb::BrakeClient client(client_config(*opts));
      client.connect();
      client.reset_alarm();
      print_readback(client.read(), false);
    });
  });

  auto* set = brake->add_subcommand("set", "set the coil current (A) or, with --torque, torque");
  add_link_options(set, *opts);
  set->add_option("VALUE", opts->value, "setpoint: A, or N·m with --torque")->required();
  set->add_flag("--torque", opts->torque, "torque mode (N·m) instead of current mode (A)");
  set->add_option("--ramp", opts->ramp, "ramp in units per second (0 = step)");
  set->callback([opts, &status] {
    run(status, [&] {
      mb::BrakeClient client(client_config(*opts));
      client.connect();
      client.set_setpoint(
          opts->value, opts->torque ? mb::BrakeMode::torque : mb::BrakeMode::current, opts->ramp);
      print_readback(client.read(), false);
    });
  });

  auto* sim = app.add_subcommand("sim-brake", "run the simulated brake controller (Modbus)");
  sim->add_option("--modbus", opts->modbus,
                  "tcp:HOST:PORT (default tcp:127.0.0.1:1502), rtu:DEVICE, or rtu:pty for a new "
                  "pseudo-terminal");
  sim->add_option("--unit", opts->unit, "Modbus unit id")->check(CLI::Range(0, 255));
  sim->add_option("--duration", opts->duration_s, "seconds to run (default: until SIGINT)");
  sim->add_option("--secret", opts->secret,
                  "take writes only after this unlock secret: hex, 'random' (the default: "
                  "printed) or 'none' (every write taken, as a real controller)");
  sim->callback([opts, &status] { run(status, [&] { run_sim_brake(*opts); }); });
}

}  // namespace wavebench::cli
