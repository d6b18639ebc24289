#include "wavebench/simdevices/powder_brake_controller.hpp"

#include <algorithm>
#include <bit>
#include <cmath>

#include "wavebench/modbus/register_codec.hpp"

namespace wavebench::simdevices {

namespace reg = brake_registers;

namespace {

float read_float(const PowderBrakeController::Table& t, int address) {
  const modbus::RegisterSpec spec{modbus::RegisterTable::holding, address,
                                  modbus::DataType::float32};
  return static_cast<float>(modbus::decode_value(spec, modbus::WordOrder::abcd, &t[address]));
}

void write_float(PowderBrakeController::Table& t, int address, double value) {
  modbus::split_u32(std::bit_cast<uint32_t>(static_cast<float>(value)), modbus::WordOrder::abcd,
                    &t[static_cast<size_t>(address)]);
}

}  // namespace

PowderBrakeController::PowderBrakeController(BrakeControllerSettings settings)
    : settings_(settings), physics_(settings.physics) {
  publish();
}

bool PowderBrakeController::output_on() const noexcept {
  return (holding_[reg::control] & reg::control_enable) != 0 && alarm_code_ == reg::alarm_none;
}

bool PowderBrakeController::torque_mode() const noexcept {
  return (holding_[reg::control] & reg::control_torque_mode) != 0;
}

double PowderBrakeController::setpoint() const {
  const double v = read_float(holding_, reg::setpoint);
  const double max =
      torque_mode() ? settings_.physics.rated_torque_nm : settings_.physics.rated_current_a;
  return std::isfinite(v) ? std::clamp(v, 0.0, max) : 0.0;
}

double PowderBrakeController::ramp() const {
  const double v = read_float(holding_, reg::setpoint_ramp);
  return std::isfinite(v) && v > 0.0 ? v : 0.0;
}

bool PowderBrakeController::write_holding(int address, int count, const uint16_t* values) {
  if (address < 0 || count < 1 || address + count > reg::table_size) return false;
  std::copy(values, values + count, holding_.begin() + address);
  auto touches = [&](int r) { return r >= address && r < address + count; };
  // Writing the timeout (re)arms the watchdog; any write of the counter feeds it.
  if (touches(reg::heartbeat) || touches(reg::watchdog_ms)) since_heartbeat_ = 0.0;
  if (touches(reg::control)) {
    if (holding_[reg::control] & reg::control_reset_alarm) {
      reset_alarms();
      holding_[reg::control] &= static_cast<uint16_t>(~reg::control_reset_alarm);
    }
    if (torque_mode() != was_torque_mode_) {
      // Carry the present output across the mode change instead of jumping.
      ramped_ =
          torque_mode() ? physics_.static_torque(ramped_) : physics_.current_for_torque(ramped_);
      was_torque_mode_ = torque_mode();
    }
  }
  publish();
  return true;
}

void PowderBrakeController::raise(uint16_t code) {
  if (alarm_code_ == reg::alarm_none) alarm_code_ = code;
  // Output off and stays off until the master resets the alarm and enables again.
  holding_[reg::control] &= static_cast<uint16_t>(~reg::control_enable);
}

void PowderBrakeController::reset_alarms() {
  watchdog_tripped_ = false;
  since_heartbeat_ = 0.0;
  if (physics_.temperature() <
      settings_.over_temperature_c - settings_.over_temperature_release_k) {
    over_temperature_ = false;
  }
  alarm_code_ = reg::alarm_none;
  if (over_temperature_) {
    alarm_code_ = reg::alarm_over_temperature;
  } else if (physics_.coil_open()) {
    alarm_code_ = reg::alarm_coil_open;
  }
}

void PowderBrakeController::step(double dt) {
  if (!(dt > 0.0)) return;
  elapsed_ += dt;
  const uint16_t watchdog_ms = holding_[reg::watchdog_ms];
  if (watchdog_ms != 0 && !watchdog_tripped_) {
    since_heartbeat_ += dt;
    if (since_heartbeat_ * 1000.0 > watchdog_ms) {
      watchdog_tripped_ = true;
      raise(reg::alarm_watchdog);
    }
  }
  if (physics_.temperature() >= settings_.over_temperature_c && !over_temperature_) {
    over_temperature_ = true;
    raise(reg::alarm_over_temperature);
  }
  if (physics_.coil_open() && output_on()) raise(reg::alarm_coil_open);

  if (output_on()) {
    const double target = setpoint();
    const double rate = ramp();
    if (rate > 0.0) {
      const double max_step = rate * dt;
      ramped_ += std::clamp(target - ramped_, -max_step, max_step);
    } else {
      ramped_ = target;
    }
  } else {
    ramped_ = 0.0;  // output off is immediate: the safe state does not ramp
  }
  physics_.set_coil_current(torque_mode() ? physics_.current_for_torque_from_here(ramped_)
                                          : ramped_);
  physics_.step(dt);
  publish();
}

void PowderBrakeController::publish() {
  uint16_t status = 0;
  if (output_on()) status |= reg::status_output_on;
  if (alarm_code_ != reg::alarm_none) status |= reg::status_alarm;
  if (over_temperature_) status |= reg::status_over_temperature;
  if (watchdog_tripped_) status |= reg::status_watchdog_tripped;
  if (physics_.coil_open()) status |= reg::status_coil_open;
  if (output_on() && ramped_ == setpoint() &&
      std::abs(physics_.torque_capacity() - physics_.target_torque()) <=
          settings_.at_setpoint_band * settings_.physics.rated_torque_nm) {
    status |= reg::status_at_setpoint;
  }
  input_[reg::status] = status;
  write_float(input_, reg::coil_current, physics_.coil_current());
  write_float(input_, reg::torque, physics_.torque_capacity());
  write_float(input_, reg::temperature, physics_.temperature());
  write_float(input_, reg::slip_power, physics_.slip_power());
  input_[reg::alarm_code] = alarm_code_;
}

}  // namespace wavebench::simdevices
