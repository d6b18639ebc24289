#pragma once
// A fast Bench for unit tests: the Bench interface directly on SimulatedBenchPlant, with a
// trapezoidal profile, a P position / PI velocity loop, a brake that follows its setpoint
// (optionally ramped), and noisy output encoder and torque sensor. No CAN, no Modbus: it
// tests the procedures' logic and their numbers against the plant's own parameters.

#include <atomic>
#include <mutex>
#include <random>
#include <vector>

#include "wavebench/bench/bench.hpp"
#include "wavebench/simdevices/bench_plant.hpp"
#include "wavebench/simdevices/motion_profile.hpp"

namespace wavebench::procedures::testing {

struct PlantBenchOptions {
  double output_noise_rad = 2.4e-6;  // 0.5 arcsec
  double torque_noise_nm = 0.02;
  double acceleration = 314;  // input profile [rad/s^2]
  double max_motor_torque = 3.9;
  double rated_torque_nm = 80;
  double max_brake_torque_nm = 100;
  unsigned seed = 7;
  // Trip with this reason once bench time passes trip_at_s (0 = never): a safety trigger.
  double trip_at_s = 0;
  std::string trip_reason = "over-torque";
};

class PlantBench final : public bench::Bench {
 public:
  explicit PlantBench(model::GearParams gear, PlantBenchOptions options = {});

  const bench::BenchDescription& description() const noexcept override { return description_; }
  void connect() override;
  void disconnect() noexcept override;
  bench::BenchLifecycle state() const noexcept override { return lifecycle_.load(); }
  std::string fault_reason() const override;
  void clear_fault() override;

  void move_input_to(double theta_in_rad, double speed_rad_s) override;
  void run_input_velocity(double omega_in_rad_s) override;
  void stop_motion() override;
  void set_brake_torque(double torque_nm, double ramp_nm_per_s = 0) override;
  void wait_for(double seconds) override;
  bool wait_until(const std::function<bool()>& done, double timeout_s) override;
  double now() const override { return static_cast<double>(syncs_) * kSyncPeriod; }
  const storage::SyncSample& latest_sample() const override { return latest_; }

  void add_observer(bench::SampleObserver& observer) override;
  void remove_observer(bench::SampleObserver& observer) override;
  bench::AcquisitionStats acquisition_stats() const override;
  void request_stop(const std::string& reason) noexcept override;

  // Counted only: the plant has no power stage to switch off.
  void deactivate() noexcept override { ++deactivations_; }
  int deactivations() const { return deactivations_; }

  simdevices::SimulatedBenchPlant& plant() { return plant_; }
  double brake_setting() const { return brake_; }

 private:
  static constexpr double kSyncPeriod = 1e-3;
  int deactivations_ = 0;
  static constexpr int kControlSteps = 4;  // 250 us servo period
  enum class Mode { kHold, kPosition, kVelocity };

  void require_ready();
  void cycle();  // one SYNC period: control, plant, sample, observers, safety
  void trip(const std::string& reason);

  bench::BenchDescription description_;
  PlantBenchOptions options_;
  simdevices::SimulatedBenchPlant plant_;
  simdevices::MotionProfile profile_;
  Mode mode_ = Mode::kHold;
  double target_ = 0, speed_ = 0, velocity_target_ = 0;
  double integral_ = 0;
  double brake_ = 0, brake_target_ = 0, brake_ramp_ = 0;
  std::uint64_t syncs_ = 0;
  storage::SyncSample latest_;
  std::vector<bench::SampleObserver*> observers_;
  std::mt19937_64 rng_;
  std::normal_distribution<double> unit_{0.0, 1.0};
  std::atomic<bench::BenchLifecycle> lifecycle_{bench::BenchLifecycle::kUnconfigured};
  std::atomic<bool> stop_requested_{false};
  mutable std::mutex reason_mutex_;
  std::string reason_, stop_reason_;
};

}  // namespace wavebench::procedures::testing
