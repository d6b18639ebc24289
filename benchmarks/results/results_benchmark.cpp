// Sample-log appends per second (1 kHz SYNC needs 1000/s with a wide margin), the lost-motion
// fit and the dynamic-TE analysis of one output revolution at 100 rpm.
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <numbers>
#include <string>

#include "wavebench/metrology/dynamic_te_analysis.hpp"
#include "wavebench/metrology/lost_motion_fit.hpp"
#include "wavebench/storage/sample_log.hpp"

namespace {

using namespace wavebench;

void BM_SampleLogAppend(benchmark::State& state) {
  const auto path = std::filesystem::temp_directory_path() /
                    ("wavebench-bench-" + std::to_string(::getpid()) + ".wbs");
  {
    storage::SampleLogWriter writer(path);
    storage::SyncSample s;
    s.flags = storage::kAllChannelsValid;
    std::uint64_t i = 0;
    for (auto _ : state) {
      s.sync_counter = static_cast<std::uint32_t>(i % 240 + 1);
      s.receive_time_ns = static_cast<std::int64_t>(i) * 1'000'000;
      s.theta_in_rad = 1e-3 * static_cast<double>(i++);
      benchmark::DoNotOptimize(writer.append(s));
    }
  }
  state.SetItemsProcessed(state.iterations());
  std::filesystem::remove(path);
}
BENCHMARK(BM_SampleLogAppend);

void BM_LostMotionFit(benchmark::State& state) {
  metrology::ThreeSegmentStiffness curve{6.7e4, 1.1e5, 1.2e5, 29, 108, 0};
  std::vector<metrology::TorqueTwistPoint> rec;
  for (int travel : {1, -1}) {
    for (int k = 1; k <= 30; ++k) {
      const double t = travel * 5.0 * k;
      rec.push_back({t, travel * 1e-4 + curve.twist_at(t), travel});
    }
  }
  metrology::LostMotionOptions options;
  options.rated_torque_nm = 100;
  for (auto _ : state) benchmark::DoNotOptimize(metrology::analyse_lost_motion(rec, options));
}
BENCHMARK(BM_LostMotionFit)->Unit(benchmark::kMillisecond);

void BM_DynamicTeOneOutputRevolution(benchmark::State& state) {
  const double n_ratio = 80, omega = 100.0 / 60 * 2 * std::numbers::pi;
  std::vector<double> t, th1, th2;
  for (int i = 0; i < 50000; ++i) {
    const double time = 1e-3 * i;
    t.push_back(time);
    th1.push_back(omega * time);
    th2.push_back(omega * time / n_ratio + 1e-4 * std::sin(2 * omega * time * (1 + 1 / n_ratio)));
  }
  analysis::SpectrumAnalyser analyser;
  for (auto _ : state) {
    benchmark::DoNotOptimize(metrology::analyse_dynamic_te(
        t, th1, th2, metrology::GearSense{n_ratio, 1}, metrology::GearTeeth{160, 162, 2}, {},
        metrology::DynamicTeOptions{}, analyser));
  }
}
BENCHMARK(BM_DynamicTeOneOutputRevolution)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
