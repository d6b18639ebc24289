// The twin driven by a measured run of a known gear: with the gear's own parameters it
// predicts the TE to within the sensors' noise; with the nominal ones the residual is large.
#include "wavebench/twin/measured_drive_twin.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <stdexcept>

#include "synthetic_run.hpp"
#include "wavebench/twin/twin_overlay.hpp"

namespace wavebench::twin {
namespace {

using testing::kArcsec;

const testing::SyntheticRun& forward_run() {
  // Run-in, forward at 600 rpm through one output revolution unloaded, then at a 20 N*m brake.
  static const testing::SyntheticRun run = testing::synthesise_run(
      testing::true_gear(), {{600, 0, 0.3, false}, {600, 0, 5.2}, {600, 20, 1.5}});
  return run;
}

double rms_arcsec(const std::vector<TwinPoint>& points, std::size_t skip) {
  double squares = 0;
  std::size_t n = 0;
  for (std::size_t i = skip; i < points.size(); ++i) {
    const double r = points[i].measured_te_rad - points[i].predicted_te_rad;
    squares += r * r;
    ++n;
  }
  return std::sqrt(squares / static_cast<double>(n)) / kArcsec;
}

TEST(MeasuredDriveTwin, ExactParametersPredictTeWithinTheSensorNoise) {
  const auto& run = forward_run();
  const auto gear = testing::true_gear();
  const auto points = replay_twin(gear, testing::sense_of(gear), run.samples);
  ASSERT_EQ(points.size(), run.samples.size());
  for (const auto& p : points) ASSERT_TRUE(std::isfinite(p.predicted_te_rad)) << p.index;
  // Predicted against the plant's true TE, after the twin's own start (its first 0.1 s): what
  // is left is the sensors' noise moving the twin, well below the noise itself.
  double squares = 0;
  for (std::size_t i = 100; i < points.size(); ++i) {
    squares += std::pow(points[i].predicted_te_rad - run.true_te_rad[i], 2);
  }
  const double model_error =
      std::sqrt(squares / static_cast<double>(points.size() - 100)) / kArcsec;
  const double residual = rms_arcsec(points, 0);
  std::printf("noise floor %.3f arcsec, residual %.3f arcsec, twin vs truth %.3f arcsec\n",
              run.noise_floor_arcsec, residual, model_error);
  EXPECT_LT(model_error, 0.3 * run.noise_floor_arcsec);
  EXPECT_LT(residual, 1.05 * run.noise_floor_arcsec);
}

TEST(MeasuredDriveTwin, NominalParametersLeaveALargeResidual) {
  const auto& run = forward_run();
  const auto gear = testing::nominal_gear();
  const auto points = replay_twin(gear, testing::sense_of(gear), run.samples);
  const double residual = rms_arcsec(points, 0);
  std::printf("nominal residual %.3f arcsec\n", residual);
  EXPECT_GT(residual, 10 * run.noise_floor_arcsec);
}

TEST(MeasuredDriveTwin, ChunkingDoesNotChangeThePrediction) {
  // Pushing sample by sample (the live twin) and replaying give the same numbers, because the
  // PCHIP slopes at the integrated samples only depend on their neighbours.
  const auto& run = forward_run();
  const auto gear = testing::true_gear();
  const std::span<const storage::SyncSample> first(run.samples.data(), 400);
  const auto whole = replay_twin(gear, testing::sense_of(gear), first);
  MeasuredDriveTwin twin(gear, testing::sense_of(gear));
  for (const auto& s : first) twin.push(twin_input(s));
  EXPECT_LT(twin.predicted(), first.size());      // one sample behind until flushed
  EXPECT_GE(twin.predicted(), first.size() - 8);  // and the torque smoother's six
  // What settled so far, then the rest: the same points as the replay, each once.
  std::vector<TwinPoint> points;
  const std::size_t settled = twin.take_settled_points(points);
  EXPECT_GE(settled, first.size() - 8);
  for (const auto& p : points) EXPECT_TRUE(std::isfinite(p.predicted_te_rad)) << p.index;
  twin.flush();
  twin.take_settled_points(points);
  EXPECT_TRUE(twin.take_points().empty());
  ASSERT_EQ(points.size(), whole.size());
  for (std::size_t i = 0; i < whole.size(); ++i) {
    EXPECT_EQ(points[i].index, whole[i].index);
    EXPECT_DOUBLE_EQ(points[i].predicted_te_rad, whole[i].predicted_te_rad) << i;
  }
}

TEST(MeasuredDriveTwin, SamplesWithoutInputAngleAreSkippedNotFilled) {
  const auto& run = forward_run();
  std::vector<storage::SyncSample> samples(run.samples.begin(), run.samples.begin() + 200);
  samples[50].flags &= ~storage::kThetaInValid;
  samples[51].flags &= ~storage::kThetaOutValid;
  samples[52].flags &= ~storage::kTorqueValid;
  const auto gear = testing::true_gear();
  const auto points = replay_twin(gear, testing::sense_of(gear), samples);
  ASSERT_EQ(points.size(), samples.size());
  EXPECT_TRUE(std::isnan(points[50].predicted_te_rad));
  EXPECT_TRUE(std::isnan(points[50].measured_te_rad));
  EXPECT_TRUE(std::isfinite(points[51].predicted_te_rad));
  EXPECT_TRUE(std::isnan(points[51].measured_te_rad));
  EXPECT_TRUE(std::isfinite(points[52].predicted_te_rad));
  EXPECT_NEAR(points[60].predicted_te_rad, run.true_te_rad[60], 2 * kArcsec);
}

TEST(MeasuredDriveTwin, RefusesATwinWhoseRatioIsNotTheBenchs) {
  const auto gear = testing::true_gear();
  EXPECT_THROW(MeasuredDriveTwin(gear, metrology::GearSense{100, 1}), std::invalid_argument);
}

TEST(TwinOverlay, CsvHasOneRowPerPointAndTheResidual) {
  const auto& run = forward_run();
  const auto gear = testing::true_gear();
  const std::span<const storage::SyncSample> first(run.samples.data(), 50);
  auto points = replay_twin(gear, testing::sense_of(gear), first);
  points[3].measured_te_rad = std::nan("");
  const auto dir = std::filesystem::path(WAVEBENCH_BINARY_DIR) / "twin_overlay_test";
  std::filesystem::create_directories(dir);
  write_twin_csv(dir / "twin.csv", points);
  std::ifstream in(dir / "twin.csv");
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "t,index,measured_te_arcsec,predicted_te_arcsec,residual_arcsec");
  std::vector<std::string> rows;
  while (std::getline(in, line)) rows.push_back(line);
  ASSERT_EQ(rows.size(), 50u);
  EXPECT_NE(rows[3].find(",3,,"), std::string::npos) << rows[3];
  double t, m, p, r;
  unsigned long long idx;
  ASSERT_EQ(std::sscanf(rows[10].c_str(), "%lf,%llu,%lf,%lf,%lf", &t, &idx, &m, &p, &r), 5);
  EXPECT_EQ(idx, 10u);
  EXPECT_NEAR(r, m - p, 2e-4);
  EXPECT_NEAR(m, points[10].measured_te_rad / kArcsec, 1e-4);

  const auto residual = twin_overlay_residual(points);
  EXPECT_EQ(residual.samples, 49u);  // the point without a measurement is left out
  EXPECT_GT(residual.rms_arcsec, 0);
}

}  // namespace
}  // namespace wavebench::twin
