#include "wavebench/bench/units_motion_check.hpp"

#include <fmt/format.h>

#include <cmath>
#include <numbers>

#include "wavebench/bench/encoder_input_speed.hpp"

namespace wavebench::bench {
namespace {

constexpr double kTwoPi = 2 * std::numbers::pi;
constexpr double kRpm = kTwoPi / 60;  // rad/s per rpm

// Watches every sample of the motion: the bound (stopping the bench at once), the encoder's
// travel and the drive's own position and velocity integral beside it.
class MotionWatch final : public SampleObserver {
 public:
  MotionWatch(Bench& bench, double speed_bound_rad_s, double travel_bound_rad)
      : bench_(bench),
        sense_(bench.description().sense),
        speed_(sense_, 5e-3),
        speed_bound_(speed_bound_rad_s),
        travel_bound_(travel_bound_rad) {}

  void on_sample(const storage::SyncSample& s) noexcept override {
    constexpr auto kNeeded = storage::kThetaInValid | storage::kThetaOutValid;
    if ((s.flags & kNeeded) != kNeeded) return;
    if (!started_) {
      started_ = true;
      out0_ = s.theta_out_rad;
      in0_ = s.theta_in_rad;
      last_ns_ = s.receive_time_ns;
      return;
    }
    if (s.valid(storage::kInputSpeedValid) && s.receive_time_ns > last_ns_)
      drive_speed_integral_ += s.input_speed_rad_s * (s.receive_time_ns - last_ns_) * 1e-9;
    last_ns_ = s.receive_time_ns;
    encoder_travel_ = sense_.ratio * sense_.direction_sign * (s.theta_out_rad - out0_);
    drive_travel_ = s.theta_in_rad - in0_;
    if (const auto v = speed_.add(s.receive_time_ns, s.theta_out_rad))
      peak_speed_ = std::max(peak_speed_, std::abs(*v));
    if (bounded_stop_) return;
    if (peak_speed_ > speed_bound_ || std::abs(encoder_travel_) > travel_bound_) {
      bounded_stop_ = true;
      bench_.request_stop(fmt::format(
          "units check: the input turned {:.1f} rpm, {:.3f} rev by the output encoder x ratio, "
          "beyond the check's bound ({:.1f} rpm, {:.3f} rev)",
          peak_speed_ / kRpm, encoder_travel_ / kTwoPi, speed_bound_ / kRpm,
          travel_bound_ / kTwoPi));
    }
  }

  double encoder_travel() const { return encoder_travel_; }
  double drive_travel() const { return drive_travel_; }
  double drive_speed_integral() const { return drive_speed_integral_; }
  double peak_speed() const { return peak_speed_; }
  bool bounded_stop() const { return bounded_stop_; }

 private:
  Bench& bench_;
  model::GearSense sense_;
  EncoderInputSpeed speed_;
  double speed_bound_, travel_bound_;
  bool started_ = false, bounded_stop_ = false;
  double out0_ = 0, in0_ = 0;
  std::int64_t last_ns_ = 0;
  double encoder_travel_ = 0, drive_travel_ = 0, drive_speed_integral_ = 0, peak_speed_ = 0;
};

struct Observing {
  Observing(Bench& bench, SampleObserver& o) : bench_(bench), o_(o) { bench_.add_observer(o_); }
  ~Observing() { bench_.remove_observer(o_); }
  Bench& bench_;
  SampleObserver& o_;
};

}  // namespace

std::string likely_drive_unit(double per_rev, double counts_per_revolution, bool velocity) {
  struct Named {
    const char* name;
    double per_rev;
  };
  const Named velocities[] = {{"counts/s", counts_per_revolution},
                              {"rpm", 60},
                              {"0.1 rpm", 600},
                              {"0.01 rpm", 6000},
                              {"rev/s", 1},
                              {"0.001 rev/s", 1000},
                              {"deg/s", 360},
                              {"0.1 deg/s", 3600},
                              {"rad/s", kTwoPi}};
  const Named positions[] = {{"counts", counts_per_revolution},
                             {"rev", 1},
                             {"0.001 rev", 1000},
                             {"deg", 360},
                             {"0.01 deg", 36000},
                             {"0.001 deg", 360000},
                             {"rad", kTwoPi},
                             {"0.001 rad", 1000 * kTwoPi}};
  // Within 25 %: an integer 0x606C in a coarse unit (rpm) truncates at the check's slow speeds
  // and lags the encoder in the ramps; the names above are at least 1.6× apart.
  const Named* best = nullptr;
  double best_error = std::log(1.25);
  const auto consider = [&](const Named& n) {
    const double error = std::abs(std::log(std::abs(per_rev) / n.per_rev));
    if (error < best_error) {
      best_error = error;
      best = &n;
    }
  };
  if (velocity) {
    for (const auto& n : velocities) consider(n);
  } else {
    for (const auto& n : positions) consider(n);
  }
  if (best) return fmt::format("{} ({:.4g} per rev{})", best->name, per_rev, velocity ? "/s" : "");
  return fmt::format("{:.4g} per rev{}", per_rev, velocity ? "/s" : "");
}

UnitsMotionResult check_units_by_motion(Bench& bench, const DriveSettings& drive,
                                        const UnitsMotionOptions& o) {
  UnitsMotionResult r;
  const double speed = o.speed_rpm * kRpm;
  const double travel = o.travel_rev * kTwoPi;
  MotionWatch watch(bench, o.speed_bound * speed, o.travel_bound * travel);
  std::string aborted;
  {
    Observing observing(bench, watch);
    try {
      bench.run_input_velocity(speed);
      // Twice the time the travel takes at the commanded speed, and the ramp.
      bench.wait_until([&] { return std::abs(watch.encoder_travel()) >= travel; },
                       2 * travel / speed + 0.5);
      bench.stop_motion();
      // stop_motion judges standstill by 0x606C, which wrong units may misread: give the
      // deceleration its time with the encoder still watching.
      bench.wait_for(0.2);
    } catch (const std::exception& e) {
      aborted = e.what();
    }
    // Let a quick stop end before the drive is switched off.
    if (!aborted.empty()) bench.idle_for(0.5);
    bench.deactivate();
    if (bench.state() == BenchLifecycle::kFault) {
      try {
        bench.clear_fault();
      } catch (const std::exception& e) {
        aborted += std::string("; the fault was not cleared: ") + e.what();
      }
    }
  }
  r.bounded_stop = watch.bounded_stop();
  r.encoder_travel_rad = watch.encoder_travel();
  r.encoder_peak_rpm = watch.peak_speed() / kRpm;
  const double moved = r.encoder_travel_rad;
  std::string how = fmt::format(
      "units check by motion: {} rpm commanded through drive.velocity_unit = {}; the output "
      "encoder x ratio measured {:.4f} rev, peak {:.1f} rpm{}",
      o.speed_rpm, drive.velocity_unit.text, moved / kTwoPi, r.encoder_peak_rpm,
      r.bounded_stop ? " (stopped by the check's bound)" : "");
  if (!aborted.empty() && !r.bounded_stop) how += "; the motion ended early: " + aborted;
  // A bounded stop may end it within a few ms: 1/50 of the intended travel (0.002 input rev,
  // ~20 counts of a 2^20 output encoder at N = 100) still tells a ratio within a few %, enough
  // for units that differ by 10× or more; less cannot be compared.
  if (std::abs(moved) < 0.02 * travel) {
    r.detail = how + ": too little travel to compare the drive's units with the encoders";
    return r;
  }
  r.position_ratio = watch.drive_travel() / moved;
  r.velocity_ratio = watch.drive_speed_integral() / moved;
  const double cpr = drive.counts_per_revolution;
  const auto judge = [&](double ratio, const char* what, const DriveUnitChoice& unit,
                         bool velocity) -> std::string {
    if (ratio >= o.min_ratio && ratio <= o.max_ratio) return {};
    const double actual = ratio * unit.units_per_rev(cpr);
    return fmt::format(
        "drive {} reads {:.4g}x the encoders: the drive's {} unit is likely {}, {} = {}", what,
        ratio, what, likely_drive_unit(actual, cpr, velocity),
        velocity ? "drive.velocity_unit" : "drive.position_unit", unit.text);
  };
  using K = DriveUnitChoice::Kind;
  std::string wrong;
  if (drive.position_unit.kind != K::kFactorGroup)
    wrong = judge(r.position_ratio, "position", drive.position_unit, false);
  if (drive.velocity_unit.kind != K::kFactorGroup) {
    const auto v = judge(r.velocity_ratio, "velocity", drive.velocity_unit, true);
    if (!v.empty()) wrong += (wrong.empty() ? "" : "; ") + v;
  }
  r.ok = wrong.empty() && !r.bounded_stop;
  if (r.ok) {
    r.detail = how + fmt::format(
                         "; the drive's position reads {:.3f}x and its velocity {:.3f}x "
                         "the encoders: the units agree",
                         r.position_ratio, r.velocity_ratio);
  } else {
    r.detail = how + "; " +
               (wrong.empty() ? fmt::format("position {:.3f}x, velocity {:.3f}x the encoders",
                                            r.position_ratio, r.velocity_ratio)
                              : wrong);
  }
  return r;
}

}  // namespace wavebench::bench
