#include "wavebench/simdevices/simulated_bench.hpp"

#include <algorithm>
#include <system_error>

namespace wavebench::simdevices {

SimulatedBench::SimulatedBench(const SimulatedBenchConfig& config, can::CanBus& bus)
    : config_(config),
      bus_(bus),
      plant_(config.gear),
      drive_(config.drive, sink()),
      encoder_(config.encoder, sink()),
      torque_sensor_(config.torque_sensor, sink()),
      direction_sign_(config.gear.geometry.direction_sign < 0 ? -1 : 1),
      timer_(bus.context()) {
  if (config.input_encoder) input_encoder_.emplace(*config.input_encoder, sink());
  plant_.set_brake_torque(config.brake_torque);
  observe_sensors();
}

SimulatedBench::~SimulatedBench() {
  stop();
}

FrameSink SimulatedBench::sink() {
  return [this](std::uint32_t cob_id, std::span<const std::uint8_t> data) {
    std::error_code ec;
    bus_.send(can::Frame::make(cob_id, data), ec);
    if (ec) {
      ++send_errors_;
    } else {
      ++frames_sent_;
    }
  };
}

void SimulatedBench::start() {
  subscription_ = bus_.on_frame([this](const can::Frame& f) { handle(f); });
  running_ = true;
  drive_.boot(now_);
  encoder_.boot(now_);
  torque_sensor_.boot(now_);
  if (input_encoder_) input_encoder_->boot(now_);
  if (config_.clock == BenchClock::kRealTime) {
    t0_ = std::chrono::steady_clock::now() -
          std::chrono::duration_cast<std::chrono::steady_clock::duration>(
              std::chrono::duration<double>(now_));
    schedule_tick();
  }
}

void SimulatedBench::stop() {
  running_ = false;
  subscription_.reset();
  timer_.cancel();
}

void SimulatedBench::schedule_tick() {
  timer_.expires_after(std::chrono::duration_cast<std::chrono::steady_clock::duration>(
      std::chrono::duration<double>(config_.tick)));
  timer_.async_wait([this](const boost::system::error_code& ec) {
    if (ec || !running_) return;
    follow_real_time();
    schedule_tick();
  });
}

void SimulatedBench::follow_real_time() {
  // A machine too slow for real time (emulation, a loaded core) must not spiral: catching up a
  // growing backlog in one go would starve the bus of replies. Past a bounded catch-up the
  // simulated clock slips behind the wall clock instead, and the slip is counted.
  constexpr double kMaxCatchUp = 0.02;  // [s]
  const auto wall = std::chrono::steady_clock::now();
  const double real = std::chrono::duration<double>(wall - t0_).count();
  double lag = real - now_;
  if (lag > kMaxCatchUp) {
    const double slip = lag - kMaxCatchUp;
    t0_ += std::chrono::duration_cast<std::chrono::steady_clock::duration>(
        std::chrono::duration<double>(slip));
    real_time_slip_ += slip;
    lag = kMaxCatchUp;
  }
  if (lag > 0) advance(lag);
}

void SimulatedBench::set_silent(bool silent) noexcept {
  drive_.set_silent(silent);
  encoder_.set_silent(silent);
  torque_sensor_.set_silent(silent);
  if (input_encoder_) input_encoder_->set_silent(silent);
}

void SimulatedBench::handle(const can::Frame& frame) noexcept {
  if (frame.error || frame.extended) return;
  try {
    if (frame.rtr) {
      // Remote frames are node-guarding requests; they do not move simulated time.
      drive_.receive_remote(frame.id);
      encoder_.receive_remote(frame.id);
      torque_sensor_.receive_remote(frame.id);
      if (input_encoder_) input_encoder_->receive_remote(frame.id);
      return;
    }
    if (config_.clock == BenchClock::kRealTime) follow_real_time();
    if (config_.clock == BenchClock::kSyncDriven && frame.id == drive_.sync_cob_id()) {
      const auto us = drive_.od().get<std::uint32_t>(0x1006, 0);
      advance(us != 0 ? us * 1e-6 : config_.sync_period);
    }
    const auto payload = frame.payload();
    drive_.receive(frame.id, payload, now_);
    encoder_.receive(frame.id, payload, now_);
    torque_sensor_.receive(frame.id, payload, now_);
    if (input_encoder_) input_encoder_->receive(frame.id, payload, now_);
  } catch (...) {
    // A device model must never take the bus thread down; the frame is dropped.
  }
}

void SimulatedBench::advance(double dt) {
  // Node timers and sensors run at least every millisecond so heartbeats and event PDOs keep
  // their times even across a long advance.
  constexpr double kChunk = 1e-3;
  while (dt > 1e-12) {
    const double h = std::min(dt, kChunk);
    advance_chunk(h);
    dt -= h;
  }
}

void SimulatedBench::advance_chunk(double dt) {
  const double period = config_.drive.control_period;
  double left = dt;
  while (left > 1e-12) {
    const double h = std::min(left, period);
    const double torque = drive_.control(plant_.state(), h);
    plant_.set_motor_torque(torque);
    plant_.step(h);
    left -= h;
  }
  now_ += dt;
  if (brake_coupling_) plant_.set_brake_torque(brake_coupling_(plant_.state().omega_out, dt));
  observe_sensors();
  drive_.advance_to(now_);
  encoder_.advance_to(now_);
  torque_sensor_.advance_to(now_);
  if (input_encoder_) input_encoder_->advance_to(now_);
}

void SimulatedBench::observe_sensors() {
  const PlantState& s = plant_.state();
  drive_.observe(s);
  encoder_.observe(direction_sign_ * s.theta_out);
  torque_sensor_.observe(direction_sign_ * s.shaft_torque);
  // The motor shaft turns in the bench's input direction whatever the gear's sense.
  if (input_encoder_) input_encoder_->observe(s.theta_in);
}

}  // namespace wavebench::simdevices
