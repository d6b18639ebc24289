#pragma once
// Shared by the Modbus integration tests: a simulated controller on an ephemeral loopback port
// (or a pty) and a client config that points at it with bounded timeouts, generous enough
// for a loaded machine or an emulator.

#include <chrono>
#include <memory>
#include <thread>

#include "wavebench/modbus/brake_client.hpp"
#include "wavebench/simdevices/brake_server.hpp"
#include "wavebench/simdevices/pty_pair.hpp"

namespace wavebench::testing {

using namespace std::chrono_literals;

inline std::unique_ptr<simdevices::BrakeServer> start_tcp_brake(bool real_time = false) {
  simdevices::BrakeServerOptions o;
  o.endpoint = modbus::parse_modbus_endpoint("tcp:127.0.0.1:0");
  o.real_time = real_time;
  return simdevices::start_brake_server(o);
}

inline modbus::BrakeClientConfig client_config_tcp(int port) {
  modbus::BrakeClientConfig c;
  c.link.endpoint = modbus::parse_modbus_endpoint("tcp:127.0.0.1:" + std::to_string(port));
  c.link.response_timeout = 1000ms;
  c.link.byte_timeout = 200ms;
  c.link.link_loss_timeout = 1500ms;
  c.link.reconnect_initial_backoff = 20ms;
  c.link.reconnect_max_backoff = 200ms;
  c.heartbeat.period = 50ms;
  c.heartbeat.watchdog_timeout = 1500ms;
  return c;
}

// Polls `pred` until it holds or `limit` passes; the limit only bounds a failing test.
template <typename Pred>
bool eventually(Pred pred, std::chrono::milliseconds limit = 10s) {
  const auto end = std::chrono::steady_clock::now() + limit;
  while (std::chrono::steady_clock::now() < end) {
    if (pred()) return true;
    std::this_thread::sleep_for(10ms);
  }
  return pred();
}

}  // namespace wavebench::testing
