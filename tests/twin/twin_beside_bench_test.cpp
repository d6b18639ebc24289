// The twin as a bench observer: on_sample only queues, the twin thread predicts what a replay
// predicts, a full queue counts drops instead of waiting, lag is reported.
#include "wavebench/twin/twin_beside_bench.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "synthetic_run.hpp"
#include "wavebench/twin/twin_calibrator.hpp"

namespace wavebench::twin {
namespace {

const testing::SyntheticRun& short_run() {
  static const testing::SyntheticRun run =
      testing::synthesise_run(testing::true_gear(), {{600, 0, 0.3, false}, {600, 0, 1.5}});
  return run;
}

TEST(TwinBesideBench, PredictsWhatAReplayPredictsAndReportsLag) {
  const auto& run = short_run();
  const auto gear = testing::true_gear();
  // The points leave the twin as they settle: through on_point and into twin.csv.
  std::vector<TwinPoint> points;
  TwinBesideBenchOptions options;
  options.on_point = [&points](const TwinPoint& p) { points.push_back(p); };
  const auto dir = std::filesystem::path(WAVEBENCH_BINARY_DIR) / "twin_beside_bench_test";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  options.overlay_csv = dir / "twin.csv";
  TwinBesideBench twin(gear, testing::sense_of(gear), options);
  EXPECT_FALSE(std::filesystem::exists(dir / "twin.csv"));  // appears whole at finish()
  bench::SampleObserver& observer = twin;
  for (const auto& s : run.samples) observer.on_sample(s);
  const TwinRunReport& report = twin.finish();
  EXPECT_TRUE(report.error.empty()) << report.error;
  EXPECT_EQ(report.samples_received, run.samples.size());
  EXPECT_EQ(report.samples_dropped, 0u);
  EXPECT_EQ(report.samples_predicted, run.samples.size());
  const auto replay = replay_twin(gear, testing::sense_of(gear), run.samples);
  ASSERT_EQ(points.size(), replay.size());
  EXPECT_EQ(report.points, replay.size());
  for (std::size_t i = 0; i < replay.size(); ++i) {
    ASSERT_EQ(points[i].index, run.samples[i].index);
    EXPECT_DOUBLE_EQ(points[i].predicted_te_rad, replay[i].predicted_te_rad) << i;
  }
  // The running figures are the replay's.
  ASSERT_TRUE(report.residual.has_value());
  const auto whole = twin_overlay_residual(replay);
  EXPECT_EQ(report.residual->samples, whole.samples);
  EXPECT_NEAR(report.residual->rms_arcsec, whole.rms_arcsec, 1e-9);
  EXPECT_NEAR(report.residual->p2p_arcsec, whole.p2p_arcsec, 1e-9);
  EXPECT_NEAR(report.noise_floor_arcsec, estimate_te_noise_floor_arcsec(replay), 1e-12);
  EXPECT_GT(report.noise_floor_arcsec, 0);
  // twin.csv: a header and one row per point.
  EXPECT_EQ(report.overlay_rows, replay.size());
  std::ifstream csv(dir / "twin.csv");
  std::size_t lines = 0;
  for (std::string line; std::getline(csv, line);) ++lines;
  EXPECT_EQ(lines, replay.size() + 1);
  // Lag: at least the samples the twin holds back by design, never negative, ordered.
  EXPECT_GT(report.lag.measurements, 0u);
  EXPECT_GE(report.lag.p50_s, 0.0);
  EXPECT_LE(report.lag.p50_s, report.lag.p99_s);
  EXPECT_LE(report.lag.p99_s, report.lag.max_s);
  EXPECT_GE(report.lag.max_s, 7e-3 - 1e-9);  // one PCHIP sample + six smoother samples
  EXPECT_GT(report.solver_steps, 0);
  const auto j = to_json(report);
  EXPECT_EQ(j["samples_dropped"], 0);
  EXPECT_TRUE(j["lag"].contains("p99_s"));
  // finish() is idempotent.
  EXPECT_EQ(&twin.finish(), &report);
}

TEST(TwinBesideBench, AFullQueueCountsDropsInsteadOfWaiting) {
  const auto& run = short_run();
  const auto gear = testing::true_gear();
  TwinBesideBenchOptions options;
  options.queue_capacity = 2;
  TwinBesideBench twin(gear, testing::sense_of(gear), options);
  // Far faster than the twin can integrate: the queue overflows, on_sample keeps returning.
  for (const auto& s : run.samples) twin.on_sample(s);
  const auto& report = twin.finish();
  EXPECT_EQ(report.samples_received, run.samples.size());
  EXPECT_GT(report.samples_dropped, 0u);
  EXPECT_EQ(report.points, report.samples_received - report.samples_dropped);
  EXPECT_EQ(twin.samples_dropped(), report.samples_dropped);
}

TEST(TwinBesideBench, SamplesAfterFinishAreDroppedNotQueued) {
  const auto& run = short_run();
  const auto gear = testing::true_gear();
  TwinBesideBench twin(gear, testing::sense_of(gear));
  for (std::size_t i = 0; i < 100; ++i) twin.on_sample(run.samples[i]);
  const auto& report = twin.finish();
  EXPECT_EQ(report.points, 100u);
  twin.on_sample(run.samples[100]);
  EXPECT_EQ(twin.samples_dropped(), 1u);
}

TEST(TwinBesideBench, RefusesAGearItCannotSimulate) {
  auto gear = testing::true_gear();
  gear.inertia_output = 0;
  EXPECT_THROW(TwinBesideBench(gear, testing::sense_of(gear)), std::invalid_argument);
}

}  // namespace
}  // namespace wavebench::twin
