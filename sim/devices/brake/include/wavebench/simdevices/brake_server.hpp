#pragma once
// The simulated powder-brake controller on a Modbus port: a libmodbus server (TCP on a
// loopback or any address, or RTU on a serial device or a pty master) serving the default
// register map of PowderBrakeController, with fault injection.
//
// Clock: real time (a thread steps the physics every `step_period`) or external (the owner
// calls step(dt), e.g. to run faster than real time inside a simulated bench).
//
// For `wavebench simbench --modbus tcp:HOST:PORT`: start_brake_server() runs it in-process;
// feed set_output_speed() from the simulated gear and apply shaft_torque() to it.

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <string>
#include <thread>

#include "wavebench/modbus/modbus_endpoint.hpp"
#include "wavebench/realtime/priority_inheriting_mutex.hpp"
#include "wavebench/simdevices/brake_fault.hpp"
#include "wavebench/simdevices/powder_brake_controller.hpp"

struct _modbus;
struct _modbus_mapping_t;

namespace wavebench::simdevices {

struct BrakeServerOptions {
  // tcp: host and port (port 0 = an ephemeral port, see BrakeServer::port()); rtu: device.
  modbus::ModbusEndpoint endpoint;
  int rtu_fd = -1;  // rtu: serve on this open fd (a pty master; adopted) instead of the device
  int unit_id = 1;
  BrakeControllerSettings controller;
  // Writes accepted only from a connection that wrote this secret to the unlock registers
  // (brake_registers::unlock); unset: every write accepted. The daemon's in-process simulated
  // bench always sets one (a random one, known only to its brake client).
  std::optional<std::uint64_t> unlock_secret;
  bool real_time = true;
  std::chrono::microseconds step_period{1000};
};

class BrakeServer {
 public:
  // Binds or opens the port; throws std::runtime_error naming the endpoint and the reason.
  explicit BrakeServer(BrakeServerOptions options);
  ~BrakeServer();
  BrakeServer(const BrakeServer&) = delete;
  BrakeServer& operator=(const BrakeServer&) = delete;

  void start();
  void stop() noexcept;

  int port() const noexcept { return port_; }
  const BrakeServerOptions& options() const noexcept { return options_; }

  void inject_fault(const BrakeFault& fault);
  void clear_fault();

  // External clock: advance the controller by dt seconds (also allowed in real-time mode).
  void step(double dt);
  void set_output_speed(double rad_per_s);
  double shaft_torque(double driving_torque_nm) const;
  // Anything else, under the controller's lock (e.g. inject a coil-open fault, set the
  // temperature, read the physics).
  template <typename F>
  auto with_controller(F&& f) {
    std::lock_guard lock(controller_mutex_);
    return f(controller_);
  }

  uint64_t requests() const noexcept { return requests_; }
  // TCP: connections accepted so far, and the most open at the same time (one per master).
  uint64_t connections_accepted() const noexcept { return connections_accepted_; }
  uint64_t most_clients_at_once() const noexcept { return most_clients_at_once_; }
  uint64_t faults_committed() const noexcept { return faults_committed_; }
  // Writes refused because their connection had not unlocked, and wrong secrets.
  uint64_t writes_refused() const noexcept { return writes_refused_; }
  uint64_t wrong_secrets() const noexcept { return wrong_secrets_; }

 private:
  enum class Outcome { replied, drop_connection };
  void serve_tcp() noexcept;
  void serve_rtu() noexcept;
  void run_clock() noexcept;
  Outcome handle(int fd, const uint8_t* query, int length);
  // The unlock rule (brake_registers::unlock): nothing when the request may go on, else what
  // was done instead.
  std::optional<Outcome> refuse_locked_write(int fd, const uint8_t* query, int length);
  bool take_fault(BrakeFault& fault);
  void reply_from_unit(int fd, const uint8_t* query, int unit);
  bool sleep_unless_stopped(std::chrono::milliseconds d);

  BrakeServerOptions options_;
  _modbus* ctx_ = nullptr;
  struct MappingDeleter {
    void operator()(_modbus_mapping_t* m) const noexcept;
  };
  std::unique_ptr<_modbus_mapping_t, MappingDeleter> mapping_;
  int listen_fd_ = -1;
  int rtu_fd_ = -1;
  int port_ = 0;

  // Taken by the bench thread (shaft_torque, every millisecond of a real-clock simulated bench):
  // priority inheriting.
  mutable realtime::PriorityInheritingMutex controller_mutex_;
  PowderBrakeController controller_;

  std::mutex fault_mutex_;
  BrakeFault fault_;

  std::thread server_thread_;
  std::thread clock_thread_;
  std::mutex stop_mutex_;
  std::condition_variable stop_cv_;
  std::atomic<bool> stopping_{false};
  std::atomic<uint64_t> requests_{0};
  std::atomic<uint64_t> connections_accepted_{0};
  std::atomic<uint64_t> most_clients_at_once_{0};
  std::atomic<uint64_t> faults_committed_{0};
  std::atomic<uint64_t> writes_refused_{0};
  std::atomic<uint64_t> wrong_secrets_{0};
  std::set<int> unlocked_;  // fds of the connections that unlocked (server thread only)
};

std::unique_ptr<BrakeServer> start_brake_server(BrakeServerOptions options);

// A fresh unlock secret from the system's random source (std::random_device: getrandom).
std::uint64_t random_unlock_secret();
// "0x" and 16 hex digits, and back; parse throws std::invalid_argument saying what it expected.
std::string unlock_secret_text(std::uint64_t secret);
std::uint64_t parse_unlock_secret(const std::string& text);

}  // namespace wavebench::simdevices
