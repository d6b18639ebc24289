#include "wavebench/daemon/manual_session.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "wavebench/model/angle_units.hpp"

namespace wavebench::daemon {

namespace {

constexpr double kRadPerSPerRpm = 2 * std::numbers::pi / 60;

std::string number_text(double value) {
  if (!std::isfinite(value)) return std::isnan(value) ? "NaN" : (value > 0 ? "inf" : "-inf");
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%g", value);
  return buffer;
}

double seconds(std::chrono::steady_clock::duration d) {
  return std::chrono::duration<double>(d).count();
}

}  // namespace

// Trips the bench when a go-to loses its keep-alive: the move blocks the bench thread, and
// the samples are the only thing that still reaches this code while it does.
class ManualSession::GoToWatch : public bench::SampleObserver {
 public:
  GoToWatch(ManualSession& session, bench::Bench& bench) : session_(session), bench_(bench) {}
  void on_sample(const storage::SyncSample& /*sample*/) noexcept override {
    if (tripped_ || ++count_ % 10 != 0) return;
    Clock::time_point deadline;
    {
      std::lock_guard lock(session_.mutex_);
      deadline = session_.wanted_.alive_deadline;
    }
    if (Clock::now() <= deadline) return;
    tripped_ = true;
    bench_.request_stop("manual go-to: no keep-alive from the console for " +
                        number_text(seconds(kJogTimeout)) + " s");
  }

 private:
  ManualSession& session_;
  bench::Bench& bench_;
  std::uint64_t count_ = 0;
  bool tripped_ = false;
};

ManualSession::ManualSession(std::function<void()> wake, ManualLimits limits)
    : wake_(std::move(wake)), limits_(limits) {}

void ManualSession::set_bench(const bench::BenchDescription& description) {
  std::lock_guard lock(mutex_);
  description_ = description;
}

ManualState ManualSession::state() const {
  std::lock_guard lock(mutex_);
  ManualState s;
  s.servo_on = shown_.powered;
  s.jog_rpm = shown_.jog_rpm;
  s.goto_deg = going_deg_;
  s.brake_nm = shown_.brake_nm;
  s.last_stop = last_stop_;
  s.max_speed_rpm = limits_.max_speed_rpm;
  if (description_) {
    const double safety = description_->limits.max_input_speed_rad_s / kRadPerSPerRpm;
    if (safety > 0) s.max_speed_rpm = std::min(s.max_speed_rpm, safety);
    const double bench_max = description_->max_brake_torque_nm;
    const double safety_brake = description_->limits.max_brake_torque_nm;
    s.max_brake_torque_nm = safety_brake > 0 && bench_max > 0 ? std::min(bench_max, safety_brake)
                                                              : std::max(bench_max, safety_brake);
  }
  s.jog_timeout_s = seconds(kJogTimeout);
  s.stop_within_s = seconds(kStopBound);
  s.hold_timeout_s = seconds(kHoldTimeout);
  return s;
}

bool ManualSession::engaged() const {
  std::lock_guard lock(mutex_);
  return shown_.powered || going_deg_ || wanted_.servo_on || wanted_.jog_rpm != 0 ||
         wanted_.goto_deg || wanted_.brake_nm > 0;
}

std::optional<ManualRefusal> ManualSession::check_speed(const char* key, double speed_rpm,
                                                        bool signed_ok) const {
  const double max = state().max_speed_rpm;
  const bool in_range = std::isfinite(speed_rpm) && std::abs(speed_rpm) <= max && speed_rpm != 0 &&
                        (signed_ok || speed_rpm > 0);
  if (in_range) return std::nullopt;
  return ManualRefusal{
      400, std::string(key) + ": got " + number_text(speed_rpm) + ", expected " +
               (signed_ok ? "a speed other than 0 within ±" : "a speed above 0 up to ") +
               number_text(max) + " rpm at the input (the manual panel's limit" +
               (description_ && description_->limits.max_input_speed_rad_s > 0
                    ? ", under safety.max_input_speed = " +
                          number_text(description_->limits.max_input_speed_rad_s / kRadPerSPerRpm) +
                          " rpm)"
                    : ")")};
}

std::optional<ManualRefusal> ManualSession::jog(double speed_rpm) {
  if (auto refused = check_speed("speed_rpm", speed_rpm, true)) return refused;
  {
    std::lock_guard lock(mutex_);
    if (going_deg_ || wanted_.goto_deg) {
      return ManualRefusal{409, "going to " +
                                    number_text(going_deg_.value_or(wanted_.goto_deg.value_or(0))) +
                                    "°: wait until it is there, or stop"};
    }
    const auto now = Clock::now();
    wanted_.jog_rpm = speed_rpm;
    wanted_.jog_deadline = now + kJogTimeout;
    wanted_.alive_deadline = now + kJogTimeout;
    wanted_.hold_deadline = now + kHoldTimeout;
  }
  wake_();
  return std::nullopt;
}

bool ManualSession::stop(const std::string& why) {
  bool going = false;
  {
    std::lock_guard lock(mutex_);
    going = going_deg_.has_value();
    wanted_.jog_rpm = 0;
    wanted_.goto_deg.reset();
    // A release is the normal end of a jog: only an interrupted go-to is worth telling.
    if (going) last_stop_ = why;
  }
  wake_();
  return going;
}

std::optional<ManualRefusal> ManualSession::go_to(double angle_deg, double speed_rpm) {
  if (auto refused = check_speed("speed_rpm", speed_rpm, false)) return refused;
  // An angle within the output's turn: the move goes the shorter way round to it, so it is
  // never more than half a turn of the output.
  if (!std::isfinite(angle_deg) || std::abs(angle_deg) > limits_.max_move_deg) {
    return ManualRefusal{400, "angle_deg: got " + number_text(angle_deg) +
                                  ", expected an output angle from -" +
                                  number_text(limits_.max_move_deg) + " to " +
                                  number_text(limits_.max_move_deg) + "°"};
  }
  {
    std::lock_guard lock(mutex_);
    if (going_deg_ || wanted_.goto_deg)
      return ManualRefusal{409, "going to " + number_text(going_deg_.value_or(0)) +
                                    "° already: wait until it is there, or stop"};
    if (wanted_.jog_rpm != 0 || shown_.jog_rpm != 0)
      return ManualRefusal{409, "jogging: release the jog before going to an angle"};
    const auto now = Clock::now();
    wanted_.goto_deg = angle_deg;
    wanted_.goto_speed_rpm = speed_rpm;
    wanted_.alive_deadline = now + kJogTimeout;
    wanted_.hold_deadline = now + kHoldTimeout;
  }
  wake_();
  return std::nullopt;
}

std::optional<ManualRefusal> ManualSession::brake(double torque_nm) {
  const double max = state().max_brake_torque_nm;
  if (!std::isfinite(torque_nm) || torque_nm < 0 || torque_nm > max) {
    return ManualRefusal{
        400, "torque_nm: got " + number_text(torque_nm) + ", expected 0 to " + number_text(max) +
                 " N·m (the bench's max brake torque and safety.max_brake_torque)"};
  }
  {
    std::lock_guard lock(mutex_);
    wanted_.brake_nm = torque_nm;
    wanted_.hold_deadline = Clock::now() + kHoldTimeout;
  }
  wake_();
  return std::nullopt;
}

void ManualSession::servo(bool on) {
  {
    std::lock_guard lock(mutex_);
    wanted_.servo_on = on;
    wanted_.hold_deadline = Clock::now() + kHoldTimeout;
    if (!on) {
      // Off means nothing moves and nothing loads: the jog and the brake go with it.
      wanted_.jog_rpm = 0;
      wanted_.brake_nm = 0;
      wanted_.goto_deg.reset();
    }
  }
  wake_();
}

void ManualSession::keep_alive() {
  std::lock_guard lock(mutex_);
  const auto now = Clock::now();
  wanted_.alive_deadline = now + kJogTimeout;
  wanted_.hold_deadline = now + kHoldTimeout;
}

void ManualSession::end_all(bench::Bench& bench, const std::string& why) noexcept {
  if (applied_.powered) bench.deactivate();
  applied_ = {};
  std::lock_guard lock(mutex_);
  wanted_ = {};
  going_deg_.reset();
  shown_ = applied_;
  last_stop_ = why;
  spdlog::info("manual control ended: {}", why);
}

void ManualSession::do_go_to(bench::Bench& bench, double angle_deg, double speed_rpm) {
  const auto& sample = bench.latest_sample();
  const auto& sense = bench.description().sense;
  // The shorter way round: the difference to the angle within the turn, in (-180°, 180°].
  const double here_deg = sample.theta_out_rad * model::kDegPerRad;
  double delta_deg = std::remainder(angle_deg - here_deg, 360.0);
  if (delta_deg <= -180) delta_deg += 360;
  const double target_in =
      sample.theta_in_rad + sense.ratio * sense.direction_sign * delta_deg / model::kDegPerRad;
  applied_.powered = true;
  {
    std::lock_guard lock(mutex_);
    shown_ = applied_;
  }
  spdlog::info("manual: going to {:.1f}° at the output ({:.0f} rpm at the input)", angle_deg,
               speed_rpm);
  GoToWatch watch(*this, bench);
  bench.add_observer(watch);
  try {
    bench.move_input_to(target_in, speed_rpm * kRadPerSPerRpm);
  } catch (...) {
    bench.remove_observer(watch);
    throw;
  }
  bench.remove_observer(watch);
}

void ManualSession::serve(bench::Bench& bench) noexcept {
  try {
    const auto lifecycle = bench.state();
    if (!bench::operational(lifecycle)) {
      bool anything = applied_.powered;
      {
        std::lock_guard lock(mutex_);
        anything = anything || wanted_.servo_on || wanted_.jog_rpm != 0 || wanted_.goto_deg ||
                   wanted_.brake_nm > 0;
      }
      if (anything)
        end_all(bench, lifecycle == bench::BenchLifecycle::kFault
                           ? "the bench tripped: " + bench.fault_reason()
                           : std::string("the bench is not connected"));
      return;
    }
    Wanted w;
    {
      std::lock_guard lock(mutex_);
      const auto now = Clock::now();
      if (wanted_.jog_rpm != 0 && now > wanted_.jog_deadline) {
        wanted_.jog_rpm = 0;
        last_stop_ = "jog stopped: no keep-alive from the console for " +
                     number_text(seconds(kJogTimeout)) + " s";
        spdlog::warn("manual: {}", last_stop_);
      }
      const bool held = wanted_.servo_on || wanted_.brake_nm > 0;
      if (held && now > wanted_.hold_deadline) {
        wanted_.servo_on = false;
        wanted_.brake_nm = 0;
        last_stop_ = "servo switched off: no keep-alive from the console for " +
                     number_text(seconds(kHoldTimeout)) + " s";
        spdlog::warn("manual: {}", last_stop_);
      }
      w = wanted_;
      if (wanted_.goto_deg) {
        going_deg_ = wanted_.goto_deg;
        wanted_.goto_deg.reset();
      }
    }
    if (w.goto_deg) {
      do_go_to(bench, *w.goto_deg, w.goto_speed_rpm);
      std::lock_guard lock(mutex_);
      going_deg_.reset();
    }
    if (w.jog_rpm != applied_.jog_rpm) {
      if (w.jog_rpm == 0) {
        bench.stop_motion();
      } else {
        bench.run_input_velocity(w.jog_rpm * kRadPerSPerRpm);
        applied_.powered = true;
      }
      applied_.jog_rpm = w.jog_rpm;
    }
    if (w.brake_nm != applied_.brake_nm) {
      bench.set_brake_torque(w.brake_nm, 0);
      applied_.brake_nm = w.brake_nm;
      if (w.brake_nm > 0) applied_.powered = true;
    }
    const bool needed = w.servo_on || w.jog_rpm != 0 || w.brake_nm > 0;
    if (needed && !applied_.powered) {
      bench.activate();
      applied_.powered = true;
    } else if (!needed && applied_.powered) {
      bench.deactivate();
      applied_.powered = false;
    }
    std::lock_guard lock(mutex_);
    shown_ = applied_;
  } catch (const std::exception& e) {
    end_all(bench, std::string("manual control ended: ") + e.what());
  } catch (...) {
    end_all(bench, "manual control ended: unknown error");
  }
}

}  // namespace wavebench::daemon
