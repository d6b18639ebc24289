#pragma once
// The in-process simulated bench for tests: the shipped sim config, optionally adjusted.

#include <gtest/gtest.h>

#include <functional>
#include <memory>
#include <vector>

#include "wavebench/bench/bench.hpp"
#include "wavebench/bench/bench_config.hpp"
#include "wavebench/bench/bench_factory.hpp"
#include "wavebench/simdevices/brake_server.hpp"
#include "wavebench/simdevices/simulated_bench.hpp"

namespace wavebench::bench::testing {

inline constexpr double kRpm = 2 * M_PI / 60;

class RecordingObserver : public SampleObserver {
 public:
  void on_sample(const storage::SyncSample& s) noexcept override { samples.push_back(s); }
  std::vector<storage::SyncSample> samples;
};

inline BenchConfig sim_config(const std::function<void(BenchConfig&)>& adjust = {}) {
  auto c = default_simulated_bench_config();
  if (adjust) adjust(c);
  return c;
}

struct SimBench {
  explicit SimBench(const BenchConfig& config) : bench(make_simulated_bench(config)) {
    access = simulated_access(*bench);
    bench->add_observer(observer);
  }
  ~SimBench() { bench->remove_observer(observer); }
  // The brake controller as the simulated hardware sees it.
  bool brake_output_on() {
    return access->brake_server().with_controller(
        [](simdevices::PowderBrakeController& c) { return c.output_on(); });
  }
  bool brake_setpoint_zero() {
    return access->brake_server().with_controller([](simdevices::PowderBrakeController& c) {
      return c.holding()[10] == 0 && c.holding()[11] == 0;
    });
  }
  double brake_setpoint_raw_hi() {
    return access->brake_server().with_controller(
        [](simdevices::PowderBrakeController& c) { return double(c.holding()[10]); });
  }
  simdevices::Cia402State drive_state() { return access->devices().drive().state(); }

  std::unique_ptr<Bench> bench;
  SimulatedBenchAccess* access = nullptr;
  RecordingObserver observer;
};

}  // namespace wavebench::bench::testing
