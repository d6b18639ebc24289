#include "wavebench/modbus/brake_client.hpp"

#include <algorithm>
#include <stdexcept>
#include <system_error>
#include <vector>

#include "wavebench/modbus/register_codec.hpp"

namespace wavebench::modbus {

BrakeClient::BrakeClient(BrakeClientConfig config)
    : config_(std::move(config)),
      link_(config_.link),
      backoff_(config_.link.reconnect_initial_backoff, config_.link.reconnect_max_backoff),
      last_success_(Clock::now().time_since_epoch().count()) {}

void BrakeClient::connect() {
  const auto turn = turns_.take(TurnPriority::routine);
  try {
    link_.connect();
    backoff_.succeeded();
  } catch (const ModbusError&) {
    backoff_.failed(Clock::now());
    throw;
  }
}

void BrakeClient::disconnect() noexcept {
  try {
    const auto turn = turns_.take(TurnPriority::routine);
    link_.close();
  } catch (const std::system_error&) {  // the turn's mutex failed: close anyway
    link_.close();
  }
}

// One transaction on the link, in a routine turn unless this thread already holds one.
template <typename F>
auto BrakeClient::with_link(F&& f) {
  const auto turn = turns_.take(TurnPriority::routine);
  if (!link_.connected()) {
    const auto now = Clock::now();
    if (!backoff_.due(now)) {
      const auto wait =
          std::chrono::duration_cast<std::chrono::milliseconds>(backoff_.next_attempt() - now);
      throw ModbusError(ModbusErrorKind::not_connected, "modbus " +
                                                            to_string(config_.link.endpoint) +
                                                            ": not connected; next attempt in " +
                                                            std::to_string(wait.count()) + " ms");
    }
    connect();
  }
  try {
    if constexpr (std::is_void_v<decltype(f())>) {
      f();
      mark_success();
    } else {
      auto result = f();
      mark_success();
      return result;
    }
  } catch (const ModbusError& e) {
    // An exception response proves the controller is alive and in step with us.
    if (e.kind() == ModbusErrorKind::exception) mark_success();
    if (!link_.connected()) backoff_.failed(Clock::now());
    throw;
  }
}

double BrakeClient::read_value(const RegisterSpec& spec) {
  const auto regs = with_link(
      [&] { return link_.read_registers(spec.table, spec.address, register_count(spec.type)); });
  return decode_value(spec, config_.map.word_order, regs.data());
}

void BrakeClient::write_value(const RegisterSpec& spec, double value) {
  const auto regs = encode_value(spec, config_.map.word_order, value);
  with_link([&] { link_.write_registers(spec.address, regs); });
}

uint16_t BrakeClient::read_control() {
  return static_cast<uint16_t>(read_value(config_.map.control));
}

void BrakeClient::write_control_bit(int bit, bool on) {
  // Read and write in one turn: a safe-state write in between would be undone.
  const auto turn = turns_.take(TurnPriority::routine);
  uint16_t word = read_control();
  const auto mask = static_cast<uint16_t>(1u << bit);
  word = on ? static_cast<uint16_t>(word | mask) : static_cast<uint16_t>(word & ~mask);
  // The reset bit is a pulse: never carry a stale one along with another change.
  if (bit != config_.map.control_bits.reset_alarm) {
    word = static_cast<uint16_t>(word & ~(1u << config_.map.control_bits.reset_alarm));
  }
  write_value(config_.map.control, word);
}

void BrakeClient::enable() {
  write_control_bit(config_.map.control_bits.enable, true);
}
void BrakeClient::disable() {
  write_control_bit(config_.map.control_bits.enable, false);
}

void BrakeClient::reset_alarm() {
  write_control_bit(config_.map.control_bits.reset_alarm, true);
  write_control_bit(config_.map.control_bits.reset_alarm, false);
}

void BrakeClient::set_mode(BrakeMode mode) {
  write_control_bit(config_.map.control_bits.torque_mode, mode == BrakeMode::torque);
}

void BrakeClient::set_setpoint(double value, BrakeMode mode, double ramp_per_s) {
  const bool torque = mode == BrakeMode::torque;
  const double max = torque ? config_.limits.max_torque_nm : config_.limits.max_current_a;
  if (!(value >= 0.0 && value <= max)) {
    throw std::invalid_argument(std::string("brake setpoint ") + std::to_string(value) +
                                (torque ? " N·m" : " A") + ": expected 0.." + std::to_string(max) +
                                (torque ? " (limits.max_torque_nm)" : " (limits.max_current_a)"));
  }
  if (!(ramp_per_s >= 0.0 && ramp_per_s <= config_.limits.max_ramp_per_s)) {
    throw std::invalid_argument(
        "brake setpoint ramp " + std::to_string(ramp_per_s) + " per s: expected 0.." +
        std::to_string(config_.limits.max_ramp_per_s) + " (limits.max_ramp_per_s, 0 = step)");
  }
  set_mode(mode);
  write_value(config_.map.setpoint_ramp, ramp_per_s);
  write_value(config_.map.setpoint, value);
}

void BrakeClient::make_safe() {
  const auto turn = turns_.take(TurnPriority::safety);
  disable();
  write_value(config_.map.setpoint_ramp, 0.0);
  write_value(config_.map.setpoint, 0.0);
}

void BrakeClient::set_watchdog(std::chrono::milliseconds timeout) {
  write_value(config_.map.watchdog_timeout_ms, static_cast<double>(timeout.count()));
}

void BrakeClient::heartbeat() {
  const auto turn = turns_.take(TurnPriority::routine);  // the counter is the turn's too
  const uint16_t next = static_cast<uint16_t>(heartbeat_counter_ + 1);
  with_link([&] { link_.write_registers(config_.map.heartbeat.address, {next}); });
  heartbeat_counter_ = next;
}

BrakeReadback BrakeClient::read() {
  const auto& m = config_.map;
  const RegisterSpec* specs[] = {&m.status,      &m.coil_current, &m.torque,
                                 &m.temperature, &m.slip_power,   &m.alarm_code};
  // One request per table when the values sit close together, which they do in most maps.
  std::vector<double> values(std::size(specs));
  for (const RegisterTable table : {RegisterTable::input, RegisterTable::holding}) {
    int lo = 65536;
    int hi = -1;
    for (const auto* s : specs) {
      if (s->table != table) continue;
      lo = std::min(lo, s->address);
      hi = std::max(hi, s->address + register_count(s->type) - 1);
    }
    if (hi < 0) continue;
    if (hi - lo + 1 <= 125) {
      const auto regs = with_link([&] { return link_.read_registers(table, lo, hi - lo + 1); });
      for (size_t i = 0; i < std::size(specs); ++i) {
        if (specs[i]->table != table) continue;
        values[i] = decode_value(*specs[i], m.word_order, regs.data() + (specs[i]->address - lo));
      }
    } else {
      for (size_t i = 0; i < std::size(specs); ++i) {
        if (specs[i]->table == table) values[i] = read_value(*specs[i]);
      }
    }
  }
  BrakeReadback r;
  r.status = decode_status(static_cast<uint16_t>(values[0]), m.status_bits);
  r.coil_current_a = values[1];
  r.torque_nm = values[2];
  r.temperature_c = values[3];
  r.slip_power_w = values[4];
  r.alarm_code = static_cast<int>(values[5]);
  r.alarm_text = describe_alarms(r.status, r.alarm_code, m);
  return r;
}

}  // namespace wavebench::modbus
