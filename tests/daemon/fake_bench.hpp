#pragma once
// A stand-in Bench for the daemon's own tests: bench time advances one SYNC period per sample
// as fast as the test runs (a simulated clock), every sample goes to the observers, and
// request_stop trips it exactly as the contract says (the blocking call throws BenchAborted).

#include <algorithm>
#include <atomic>
#include <mutex>
#include <thread>
#include <vector>

#include "wavebench/bench/bench.hpp"

namespace wavebench::daemon::testing {

class FakeBench : public bench::Bench {
 public:
  explicit FakeBench(bool fail_connect = false) : fail_connect_(fail_connect) {
    description_.name = "fake";
    description_.unit_serial = "SN-FAKE-1";
    description_.sense.ratio = 100;
    description_.sync_period_s = 1e-3;
    description_.simulated_clock = true;
  }

  const bench::BenchDescription& description() const noexcept override { return description_; }
  void connect() override {
    if (fail_connect_) throw std::runtime_error("drive node 1: no boot-up within 1 s");
    state_ = bench::BenchLifecycle::kInactive;
  }
  void disconnect() noexcept override { state_ = bench::BenchLifecycle::kUnconfigured; }
  bench::BenchLifecycle state() const noexcept override { return state_; }
  std::string fault_reason() const override {
    std::lock_guard lock(mutex_);
    return reason_;
  }
  void clear_fault() override {
    std::lock_guard lock(mutex_);
    reason_.clear();
    state_ = bench::BenchLifecycle::kInactive;
  }
  void move_input_to(double theta, double) override {
    check();
    theta_in_ = theta;
  }
  void run_input_velocity(double omega) override {
    check();
    omega_ = omega;
  }
  void stop_motion() override {
    check();
    omega_ = 0;
  }
  void set_brake_torque(double torque, double) override {
    check();
    brake_ = torque;
  }
  void wait_for(double seconds) override {
    const auto n = static_cast<std::uint64_t>(seconds / description_.sync_period_s + 0.5);
    for (std::uint64_t i = 0; i < n; ++i) step();
  }
  bool wait_until(const std::function<bool()>& done, double timeout_s) override {
    const auto n = static_cast<std::uint64_t>(timeout_s / description_.sync_period_s + 0.5);
    for (std::uint64_t i = 0; i < n; ++i) {
      step();
      if (done()) return true;
    }
    return false;
  }
  void idle_for(double seconds) override {
    if (state_ == bench::BenchLifecycle::kUnconfigured) return;
    const auto n = static_cast<std::uint64_t>(seconds / description_.sync_period_s + 0.5);
    for (std::uint64_t i = 0; i < n; ++i) acquire();
  }
  double now() const override { return static_cast<double>(syncs_) * description_.sync_period_s; }
  const storage::SyncSample& latest_sample() const override { return latest_; }
  void add_observer(bench::SampleObserver& o) override { observers_.push_back(&o); }
  void remove_observer(bench::SampleObserver& o) override {
    observers_.erase(std::remove(observers_.begin(), observers_.end(), &o), observers_.end());
  }
  bench::AcquisitionStats acquisition_stats() const override {
    bench::AcquisitionStats s;
    s.syncs_sent = syncs_;
    s.samples = syncs_;
    s.bus_load = 0.42;
    return s;
  }
  void request_stop(const std::string& reason) noexcept override {
    std::lock_guard lock(mutex_);
    if (state_ == bench::BenchLifecycle::kFault) return;
    reason_ = reason;
    brake_ = 0;  // safe value
    omega_ = 0;  // quick stop
    state_ = bench::BenchLifecycle::kFault;
  }

  double brake_torque() const { return brake_; }

 private:
  void check() const {
    if (state_ == bench::BenchLifecycle::kFault) throw bench::BenchAborted(fault_reason());
  }
  void step() {
    check();
    acquire();
  }
  void acquire() {
    ++syncs_;
    theta_in_ += omega_.load() * description_.sync_period_s;
    latest_.sync_counter = static_cast<std::uint32_t>((syncs_ - 1) % 240 + 1);
    latest_.flags = storage::kAllChannelsValid;
    latest_.receive_time_ns = static_cast<std::int64_t>(syncs_) * 1'000'000;
    latest_.theta_in_rad = theta_in_;
    latest_.theta_out_rad = theta_in_ / description_.sense.ratio + 1e-4;
    latest_.torque_nm = brake_;
    latest_.brake_torque_nm = brake_;
    for (auto* o : observers_) o->on_sample(latest_);
    // Keep a busy test machine usable: the fake's clock is not tied to real time anyway.
    if (syncs_ % 50 == 0) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }

  bench::BenchDescription description_;
  bool fail_connect_;
  std::atomic<bench::BenchLifecycle> state_{bench::BenchLifecycle::kUnconfigured};
  mutable std::mutex mutex_;
  std::string reason_;
  std::vector<bench::SampleObserver*> observers_;
  std::atomic<std::uint64_t> syncs_{0};
  double theta_in_ = 0;
  std::atomic<double> omega_{0};  // request_stop zeroes it from another thread
  std::atomic<double> brake_{0};
  storage::SyncSample latest_;
};

}  // namespace wavebench::daemon::testing
