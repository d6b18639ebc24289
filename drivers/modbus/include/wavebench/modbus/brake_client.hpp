#pragma once
// Commands and readback of the powder-brake controller through the configured register map.
// Owns the line's one libmodbus context (issue #9: one master per RS-485 line), shared by the
// bench thread's commands and the BrakeSupervisor's heartbeats and polls: calls from several
// threads take turns on the link (link_turns.hpp), one transaction at a time, and make_safe()
// goes before every routine request that is waiting: it waits at most for the turn in progress,
// one transaction (two for another thread's read-modify-write of the control word, which must
// not be split). A lost link is reopened on the next call, no sooner than the backoff allows.

#include <atomic>
#include <chrono>
#include <cstdint>
#include <string>

#include "wavebench/modbus/brake_config.hpp"
#include "wavebench/modbus/brake_status.hpp"
#include "wavebench/modbus/link_turns.hpp"
#include "wavebench/modbus/modbus_link.hpp"
#include "wavebench/modbus/reconnect_backoff.hpp"

namespace wavebench::modbus {

enum class BrakeMode { current, torque };

struct BrakeReadback {
  BrakeStatus status;
  double coil_current_a = 0.0;
  double torque_nm = 0.0;
  double temperature_c = 0.0;
  double slip_power_w = 0.0;
  int alarm_code = 0;
  std::string alarm_text;  // decoded status bits and alarm code
};

class BrakeClient {
 public:
  using Clock = std::chrono::steady_clock;

  explicit BrakeClient(BrakeClientConfig config);
  BrakeClient(const BrakeClient&) = delete;
  BrakeClient& operator=(const BrakeClient&) = delete;

  // Connects now, whatever the backoff says. Throws ModbusError.
  void connect();
  void disconnect() noexcept;
  bool connected() const noexcept { return link_.connected(); }
  // Connections opened so far (a new one may be a restarted controller).
  uint64_t connections() const noexcept { return link_.connections(); }

  void enable();
  void disable();
  // Pulses the reset bit (set, then cleared) so controllers that act on an edge see one.
  void reset_alarm();
  void set_mode(BrakeMode mode);
  // Ramp (units per second, 0 = step) then setpoint; checks both against the limits first
  // and throws std::invalid_argument naming the value and the allowed range.
  void set_setpoint(double value, BrakeMode mode, double ramp_per_s);
  // The safe state of bench.md §7: output off first, then setpoint 0 (as a step), so the
  // brake stays released if something enables it again. Takes a safety turn on the link.
  void make_safe();
  void set_watchdog(std::chrono::milliseconds timeout);
  void heartbeat();  // writes the next counter value
  BrakeReadback read();
  uint16_t read_control();

  // Time of the last transaction that got a valid reply (exception replies count: the
  // controller is there). Construction time until then.
  Clock::time_point last_success() const noexcept {
    return Clock::time_point(Clock::duration(last_success_.load(std::memory_order_relaxed)));
  }
  const BrakeClientConfig& config() const noexcept { return config_; }
  const ReconnectBackoff& backoff() const noexcept { return backoff_; }
  uint64_t transactions() const noexcept { return link_.transactions(); }

 private:
  template <typename F>
  auto with_link(F&& f);
  double read_value(const RegisterSpec& spec);
  void write_value(const RegisterSpec& spec, double value);
  void write_control_bit(int bit, bool on);
  void mark_success() noexcept {
    last_success_.store(Clock::now().time_since_epoch().count(), std::memory_order_relaxed);
  }

  BrakeClientConfig config_;
  ModbusLink link_;
  LinkTurns turns_;
  ReconnectBackoff backoff_;  // under a turn
  std::atomic<Clock::rep> last_success_;
  uint16_t heartbeat_counter_ = 0;
};

}  // namespace wavebench::modbus
