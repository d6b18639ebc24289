#include "plant_bench.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace wavebench::procedures::testing {

PlantBench::PlantBench(model::GearParams gear, PlantBenchOptions options)
    : options_(options), plant_(gear), rng_(options.seed) {
  description_.name = "plant";
  description_.unit_serial = "PLANT-TEST";
  description_.sense = {plant_.ratio(), gear.geometry.direction_sign};
  description_.sync_period_s = kSyncPeriod;
  description_.simulated_clock = true;
  description_.rated_torque_nm = options.rated_torque_nm;
  description_.max_brake_torque_nm = options.max_brake_torque_nm;
  description_.output_encoder_noise_rad = options.output_noise_rad;
  description_.torque_noise_nm = options.torque_noise_nm;
  description_.twin_gear = std::move(gear);
}

void PlantBench::connect() {
  profile_.reset(plant_.state().theta_in);
  target_ = plant_.state().theta_in;
  lifecycle_ = bench::BenchLifecycle::kInactive;
  cycle();
}

void PlantBench::disconnect() noexcept {
  brake_ = brake_target_ = 0;
  plant_.set_brake_torque(0);
  plant_.set_motor_torque(0);
  lifecycle_ = bench::BenchLifecycle::kUnconfigured;
}

std::string PlantBench::fault_reason() const {
  std::lock_guard lock(reason_mutex_);
  return reason_;
}

void PlantBench::clear_fault() {
  stop_requested_ = false;
  {
    std::lock_guard lock(reason_mutex_);
    reason_.clear();
  }
  profile_.reset(plant_.state().theta_in, plant_.state().omega_in);
  mode_ = Mode::kHold;
  lifecycle_ = bench::BenchLifecycle::kInactive;
}

void PlantBench::require_ready() {
  if (stop_requested_) {
    std::string reason;
    {
      std::lock_guard lock(reason_mutex_);
      reason = stop_reason_;
    }
    trip(reason);
  }
  if (lifecycle_ == bench::BenchLifecycle::kFault) throw bench::BenchAborted(fault_reason());
  if (!bench::operational(lifecycle_)) {
    throw std::runtime_error("plant bench: not connected");
  }
}

void PlantBench::trip(const std::string& reason) {
  brake_ = brake_target_ = 0;
  plant_.set_brake_torque(0);
  mode_ = Mode::kVelocity;  // quick stop: velocity demand to zero
  velocity_target_ = 0;
  {
    std::lock_guard lock(reason_mutex_);
    reason_ = reason;
  }
  lifecycle_ = bench::BenchLifecycle::kFault;
  throw bench::BenchAborted(reason);
}

void PlantBench::cycle() {
  const double dt = kSyncPeriod / kControlSteps;
  const auto& gear = plant_.params();
  (void)gear;
  for (int i = 0; i < kControlSteps; ++i) {
    const auto& s = plant_.state();
    switch (mode_) {
      case Mode::kPosition:
        profile_.step_to_position(target_, speed_, options_.acceleration, options_.acceleration,
                                  dt);
        break;
      case Mode::kVelocity:
        profile_.step_to_velocity(velocity_target_, options_.acceleration, options_.acceleration,
                                  dt);
        break;
      case Mode::kHold:
        break;
    }
    // Cascade of the simulated servo drive: P position, PI velocity, torque limit.
    const double v_demand = profile_.velocity() + 120.0 * (profile_.position() - s.theta_in);
    const double error = v_demand - s.omega_in;
    double torque = 0.08 * (error + integral_ / 0.01);
    const double limited =
        std::clamp(torque, -options_.max_motor_torque, options_.max_motor_torque);
    if (limited == torque) integral_ += error * dt;
    torque = limited;
    plant_.set_motor_torque(torque);
    if (brake_ramp_ > 0) {
      const double d = brake_ramp_ * dt;
      brake_ = brake_ < brake_target_ ? std::min(brake_target_, brake_ + d)
                                      : std::max(brake_target_, brake_ - d);
    } else {
      brake_ = brake_target_;
    }
    plant_.set_brake_torque(brake_);
    plant_.step(dt);
  }
  const auto& s = plant_.state();
  ++syncs_;
  storage::SyncSample sample;
  sample.index = syncs_ - 1;
  sample.sync_counter = static_cast<std::uint32_t>((syncs_ - 1) % 240 + 1);
  sample.flags = storage::kAllChannelsValid;
  sample.receive_time_ns = static_cast<std::int64_t>(std::llround(now() * 1e9));
  sample.theta_in_rad = s.theta_in;
  sample.theta_out_rad =
      description_.sense.direction_sign * s.theta_out + options_.output_noise_rad * unit_(rng_);
  sample.input_speed_rad_s = s.omega_in;
  sample.torque_nm =
      description_.sense.direction_sign * s.shaft_torque + options_.torque_noise_nm * unit_(rng_);
  sample.brake_current_a = brake_ / 50.0;
  sample.brake_torque_nm = brake_;
  latest_ = sample;
  for (auto* o : observers_) o->on_sample(sample);
  if (options_.trip_at_s > 0 && now() >= options_.trip_at_s && bench::operational(lifecycle_)) {
    trip(options_.trip_reason);
  }
  if (stop_requested_ && bench::operational(lifecycle_)) {
    std::string reason;
    {
      std::lock_guard lock(reason_mutex_);
      reason = stop_reason_;
    }
    trip(reason);
  }
}

void PlantBench::move_input_to(double theta_in_rad, double speed_rad_s) {
  require_ready();
  if (mode_ != Mode::kPosition) profile_.reset(profile_.position(), profile_.velocity());
  mode_ = Mode::kPosition;
  target_ = theta_in_rad;
  speed_ = std::abs(speed_rad_s);
  // Target reached: the demand is on the target and the actual position within a window for
  // 5 ms (the drive's 0x6067/0x6068), as the simulated CiA 402 drive reports it.
  const double window = 20 * 2 * std::numbers::pi / 131072;
  int in_window = 0;
  const double timeout = std::abs(theta_in_rad - profile_.position()) / speed_ + 10;
  const double t_end = now() + timeout;
  while (now() < t_end) {
    cycle();
    const bool there =
        profile_.position() == target_ && std::abs(plant_.state().theta_in - target_) <= window;
    in_window = there ? in_window + 1 : 0;
    if (in_window >= 5) return;
  }
  throw std::runtime_error("plant bench: target not reached");
}

void PlantBench::run_input_velocity(double omega_in_rad_s) {
  require_ready();
  mode_ = Mode::kVelocity;
  velocity_target_ = omega_in_rad_s;
}

void PlantBench::stop_motion() {
  run_input_velocity(0);
  wait_until([&] { return profile_.velocity() == 0 && std::abs(plant_.state().omega_in) < 1e-2; },
             30);
  target_ = profile_.position();
  mode_ = Mode::kPosition;
  speed_ = 1;
}

void PlantBench::set_brake_torque(double torque_nm, double ramp_nm_per_s) {
  require_ready();
  brake_target_ = std::max(0.0, torque_nm);
  brake_ramp_ = ramp_nm_per_s;
}

void PlantBench::wait_for(double seconds) {
  require_ready();
  const double t_end = now() + seconds - 1e-9;
  while (now() < t_end) cycle();
}

bool PlantBench::wait_until(const std::function<bool()>& done, double timeout_s) {
  require_ready();
  const double t_end = now() + timeout_s - 1e-9;
  while (now() < t_end) {
    cycle();
    if (done()) return true;
  }
  return false;
}

void PlantBench::add_observer(bench::SampleObserver& observer) {
  observers_.push_back(&observer);
}

void PlantBench::remove_observer(bench::SampleObserver& observer) {
  std::erase(observers_, &observer);
}

bench::AcquisitionStats PlantBench::acquisition_stats() const {
  bench::AcquisitionStats a;
  a.syncs_sent = syncs_;
  a.samples = syncs_;
  return a;
}

void PlantBench::request_stop(const std::string& reason) noexcept {
  try {
    std::lock_guard lock(reason_mutex_);
    stop_reason_ = reason;
  } catch (...) {
  }
  stop_requested_ = true;
}

}  // namespace wavebench::procedures::testing
