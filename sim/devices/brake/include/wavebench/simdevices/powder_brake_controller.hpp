#pragma once
// The firmware of the simulated brake controller: the default register map of bench.md §3 on
// top of PowderBrakePhysics — enable, current or torque mode, setpoint ramp, watchdog, latched
// alarms (over-temperature, watchdog, coil open) and their reset. No I/O here: the Modbus
// server copies the register image in and out, and step(dt) advances simulated time.

#include <array>
#include <cstdint>

#include "wavebench/simdevices/powder_brake_physics.hpp"

namespace wavebench::simdevices {

struct BrakeControllerSettings {
  model::PowderBrakeParams physics;
  double over_temperature_c = 80.0;
  // An over-temperature alarm can be reset once the coil is this much below the limit.
  double over_temperature_release_k = 5.0;
  // At setpoint: ramp finished and torque within this fraction of rated torque of its target.
  double at_setpoint_band = 0.02;
};

namespace brake_registers {
// Holding registers.
inline constexpr int control = 0;
inline constexpr int watchdog_ms = 1;
inline constexpr int heartbeat = 2;
inline constexpr int setpoint = 10;
inline constexpr int setpoint_ramp = 12;
// Unlock (simulated controller only, issue #22): four holding registers 24..27, the 64-bit
// shared secret high word first, written in one "write multiple registers" (FC 16) by a
// connection before any other write of it is accepted. A connection that has not unlocked may
// read; its writes are answered with exception 1 (illegal function) and change nothing. A wrong
// secret is answered with exception 3 (illegal data value) and the connection is closed, so
// guessing costs a connection per try. The secret is never stored in the register table, so
// reading 24..27 gives zeros. Serial (RTU): the line is the connection. Without a secret
// (BrakeServerOptions::unlock_secret unset) every write is accepted, as a real controller does.
inline constexpr int unlock = 24;
inline constexpr int unlock_count = 4;
// Input registers.
inline constexpr int status = 0;
inline constexpr int coil_current = 10;
inline constexpr int torque = 12;
inline constexpr int temperature = 14;
inline constexpr int slip_power = 16;
inline constexpr int alarm_code = 20;
// Bits.
inline constexpr uint16_t control_enable = 1u << 0;
inline constexpr uint16_t control_reset_alarm = 1u << 1;
inline constexpr uint16_t control_torque_mode = 1u << 2;
inline constexpr uint16_t status_output_on = 1u << 0;
inline constexpr uint16_t status_alarm = 1u << 1;
inline constexpr uint16_t status_over_temperature = 1u << 2;
inline constexpr uint16_t status_watchdog_tripped = 1u << 3;
inline constexpr uint16_t status_coil_open = 1u << 4;
inline constexpr uint16_t status_at_setpoint = 1u << 5;
// Alarm codes.
inline constexpr uint16_t alarm_none = 0;
inline constexpr uint16_t alarm_over_temperature = 1;
inline constexpr uint16_t alarm_watchdog = 2;
inline constexpr uint16_t alarm_coil_open = 3;
inline constexpr int table_size = 32;
}  // namespace brake_registers

class PowderBrakeController {
 public:
  using Table = std::array<uint16_t, brake_registers::table_size>;

  explicit PowderBrakeController(BrakeControllerSettings settings = {});

  // A master wrote holding registers [address, address + count) with `values`.
  // Returns false (nothing written) if the range is outside the table.
  bool write_holding(int address, int count, const uint16_t* values);
  const Table& holding() const noexcept { return holding_; }
  const Table& input() const noexcept { return input_; }

  void step(double dt);

  PowderBrakePhysics& physics() noexcept { return physics_; }
  const PowderBrakePhysics& physics() const noexcept { return physics_; }
  const BrakeControllerSettings& settings() const noexcept { return settings_; }
  bool output_on() const noexcept;
  uint16_t alarm_code() const noexcept { return alarm_code_; }
  double ramped_setpoint() const noexcept { return ramped_; }
  double elapsed() const noexcept { return elapsed_; }

 private:
  double setpoint() const;
  double ramp() const;
  bool torque_mode() const noexcept;
  void raise(uint16_t code);
  void reset_alarms();
  void publish();

  BrakeControllerSettings settings_;
  PowderBrakePhysics physics_;
  Table holding_{};
  Table input_{};
  double ramped_ = 0.0;  // the setpoint after the ramp, in the units of the present mode
  bool was_torque_mode_ = false;
  double since_heartbeat_ = 0.0;
  bool watchdog_tripped_ = false;
  bool over_temperature_ = false;
  uint16_t alarm_code_ = brake_registers::alarm_none;
  double elapsed_ = 0.0;
};

}  // namespace wavebench::simdevices
