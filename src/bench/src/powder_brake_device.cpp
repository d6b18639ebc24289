#include "wavebench/bench/powder_brake_device.hpp"

#include <spdlog/spdlog.h>

#include <cstdio>

#include "wavebench/modbus/modbus_endpoint.hpp"

namespace wavebench::bench {

PowderBrakeDevice::PowderBrakeDevice(modbus::BrakeClientConfig config,
                                     modbus::BrakeEventSink& events)
    : BenchDevice("brake controller"), config_(std::move(config)), events_(events) {}

PowderBrakeDevice::~PowderBrakeDevice() {
  disconnect();
}

std::vector<storage::ChannelInfo> PowderBrakeDevice::channels() const {
  return {{"brake_current", "A"}, {"brake_torque", "N*m"}};
}

std::vector<CommandInterface> PowderBrakeDevice::commands() const {
  return {{"brake_torque_setpoint", "N*m"}};
}

std::string PowderBrakeDevice::describe() const {
  return name() + " at " + modbus::to_string(config_.link.endpoint);
}

void PowderBrakeDevice::connect(bool beats_in_bench_time) {
  disconnect();
  beats_in_bench_time_ = beats_in_bench_time;
  auto client = std::make_unique<modbus::BrakeClient>(config_);
  try {
    client->connect();
    client->reset_alarm();
    client->make_safe();
    client->set_mode(modbus::BrakeMode::torque);
    if (beats_in_bench_time_) client->heartbeat();
  } catch (const std::exception& e) {
    throw std::runtime_error(describe() + ": " + e.what());
  }
  client_ = std::move(client);
  next_beat_s_ = 0;
  safe_pending_ = false;
  cycle_.reset();
  supervisor_ = std::make_unique<modbus::BrakeSupervisor>(*client_, events_);
  supervisor_->start();
}

void PowderBrakeDevice::disconnect() noexcept {
  if (!client_) return;
  make_safe();
  if (supervisor_) supervisor_->stop();
  supervisor_.reset();
  try {
    client_->set_watchdog(std::chrono::milliseconds(0));
  } catch (const std::exception& e) {
    spdlog::warn("{}: watchdog not switched off: {}", describe(), e.what());
  }
  client_->disconnect();
  client_.reset();
  cycle_.reset();
}

bool PowderBrakeDevice::make_safe() noexcept {
  if (!client_) return true;
  try {
    client_->make_safe();
    safe_pending_ = false;
    return true;
  } catch (const std::exception& e) {
    safe_pending_ = true;
    spdlog::error(
        "{}: safe state not confirmed ({}); retrying when the link returns, the controller's "
        "watchdog switches the output off meanwhile",
        describe(), e.what());
    return false;
  }
}

void PowderBrakeDevice::retry_safe_state() noexcept {
  if (safe_pending_) make_safe();
}

void PowderBrakeDevice::set_torque(double torque_nm, double ramp_nm_per_s, bool output_on) {
  client_->set_setpoint(torque_nm, modbus::BrakeMode::torque, ramp_nm_per_s);
  if (output_on) client_->enable();
}

void PowderBrakeDevice::reset_after_fault() {
  client_->reset_alarm();
  client_->make_safe();
  client_->set_mode(modbus::BrakeMode::torque);
  safe_pending_ = false;
}

void PowderBrakeDevice::beat_if_due(double bench_now_s) noexcept {
  if (!beats_in_bench_time_ || !client_ || bench_now_s < next_beat_s_) return;
  next_beat_s_ = bench_now_s + std::chrono::duration<double>(config_.heartbeat.period).count();
  try {
    client_->heartbeat();
  } catch (const std::exception&) {
    // The supervisor decides when the link is lost; a missed beat is the watchdog's business.
  }
}

std::optional<modbus::BrakeReadback> PowderBrakeDevice::fresh_readback() const {
  if (!supervisor_ || supervisor_->link_lost()) return std::nullopt;
  const auto age = modbus::BrakeClient::Clock::now() - supervisor_->latest_time();
  if (age > 3 * config_.heartbeat.period + std::chrono::milliseconds(50)) return std::nullopt;
  return supervisor_->latest();
}

bool PowderBrakeDevice::link_lost() const noexcept {
  return supervisor_ && supervisor_->link_lost();
}

std::string PowderBrakeDevice::last_error() const {
  return supervisor_ ? supervisor_->last_error() : std::string();
}

void PowderBrakeDevice::on_state_change(BenchLifecycle state) noexcept {
  if (state_.exchange(state) == BenchLifecycle::kActive || state != BenchLifecycle::kActive)
    idle_since_ = modbus::BrakeClient::Clock::now().time_since_epoch().count();
}

std::optional<std::string> PowderBrakeDevice::energised_while_idle() {
  if (state_ == BenchLifecycle::kActive || !supervisor_ || !cycle_) return std::nullopt;
  if (!cycle_->status.output_on) return std::nullopt;
  using Clock = modbus::BrakeClient::Clock;
  const auto taken = supervisor_->latest_time();
  const auto idle = Clock::time_point(Clock::duration(idle_since_.load()));
  if (taken <= idle + config_.link.response_timeout + config_.heartbeat.period) return std::nullopt;
  if (taken == last_reported_) return std::nullopt;
  last_reported_ = taken;
  char values[96];
  std::snprintf(values, sizeof values, "%.3g N*m, %.3g A", cycle_->torque_nm,
                cycle_->coil_current_a);
  return describe() + " energised while the bench is " + lifecycle_name(state_.load()) +
         " (output on, " + values +
         "): something other than this daemon switched it on; output commanded off";
}

void PowderBrakeDevice::on_cycle_end(CycleRecord& record) noexcept {
  cycle_ = fresh_readback();
  if (!cycle_) return;
  put(record, 0, cycle_->coil_current_a);
  put(record, 1, cycle_->torque_nm);
}

}  // namespace wavebench::bench
