// Calibration of a nominal (wrong) twin to a run of a known gear: the residual falls to within
// 10 % of the simulated sensors' noise floor (issue #5 acceptance), backlash and stiffness come
// out near the truth, and the calibrated config loads back.
#include "wavebench/twin/twin_calibrator.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "synthetic_run.hpp"
#include "wavebench/config/twin_case.hpp"

namespace wavebench::twin {
namespace {

using testing::kArcmin;

// Forward unloaded through an output revolution, forward at 20 N*m, then reverse at a 10 N*m
// brake (which holds the output while the input crosses the backlash): both flanks, three
// loads.
const testing::SyntheticRun& calibration_run() {
  static const testing::SyntheticRun run = testing::synthesise_run(
      testing::true_gear(), {{600, 0, 0.3, false}, {600, 0, 5.2}, {600, 20, 1.5}, {-600, 10, 2.9}});
  return run;
}

const TwinCalibration& calibration() {
  static const TwinCalibration cal =
      calibrate_twin(testing::nominal_gear(), testing::sense_of(testing::nominal_gear()),
                     calibration_run().samples);
  return cal;
}

TEST(TwinCalibration, ResidualFallsToTheSensorNoiseFloor) {
  const auto& run = calibration_run();
  const auto& cal = calibration();
  std::printf("noise floor %.3f arcsec; residual before %.3f, after %.3f arcsec (%d passes)\n",
              run.noise_floor_arcsec, cal.before.rms_arcsec, cal.after.rms_arcsec, cal.passes);
  EXPECT_GT(cal.before.rms_arcsec, 10 * run.noise_floor_arcsec);
  EXPECT_LT(cal.after.rms_arcsec, cal.before.rms_arcsec);
  EXPECT_LE(cal.after.rms_arcsec, 1.1 * run.noise_floor_arcsec);
  EXPECT_GE(cal.after.samples + 8, run.samples.size());  // all but the first few overlap
  // The run's own estimate of the floor (second differences) agrees with the known one.
  EXPECT_NEAR(cal.noise_floor_arcsec, run.noise_floor_arcsec, 0.05 * run.noise_floor_arcsec);
}

TEST(TwinCalibration, FindsTheBacklashAndStiffnessOfTheUnit) {
  const auto& cal = calibration();
  std::printf("backlash %.3f arcmin (true 1.0), stiffness factor %.4f (true %.4f)\n",
              cal.calibrated.backlash.total_rad / kArcmin, cal.stiffness_factor, 6.7 / 5.0);
  EXPECT_NEAR(cal.calibrated.backlash.total_rad / kArcmin, 1.0, 0.1);
  EXPECT_NEAR(cal.stiffness_factor, 6.7 / 5.0, 0.05 * 6.7 / 5.0);
  for (const char* what : {"te_harmonics", "offset", "backlash", "stiffness"}) {
    EXPECT_NE(std::find(cal.fitted.begin(), cal.fitted.end(), what), cal.fitted.end()) << what;
  }
  const auto j = to_json(cal);
  EXPECT_DOUBLE_EQ(j["rms_after_arcsec"].get<double>(), cal.after.rms_arcsec);
  EXPECT_GT(j["te_terms"].size(), 3u);
}

TEST(TwinCalibration, CalibratedConfigLoadsBackWithTheSameParameters) {
  const auto& cal = calibration();
  const auto dir = std::filesystem::path(WAVEBENCH_BINARY_DIR) / "twin_calibrator_test";
  std::filesystem::create_directories(dir);
  const auto file = dir / "twin-calibrated.yaml";
  write_calibrated_twin_config(file, cal);
  const config::TwinCase loaded = config::load_twin_case(file);
  const auto& g = cal.calibrated;
  EXPECT_EQ(loaded.gear.name, g.name);
  ASSERT_EQ(loaded.gear.te_terms.size(), g.te_terms.size());
  for (std::size_t i = 0; i < g.te_terms.size(); ++i) {
    EXPECT_EQ(loaded.gear.te_terms[i].source, g.te_terms[i].source);
    EXPECT_DOUBLE_EQ(loaded.gear.te_terms[i].amplitude_rad, g.te_terms[i].amplitude_rad);
    EXPECT_DOUBLE_EQ(loaded.gear.te_terms[i].phase_rad, g.te_terms[i].phase_rad);
    EXPECT_DOUBLE_EQ(loaded.gear.te_terms[i].order_input, g.te_terms[i].order_input);
    EXPECT_DOUBLE_EQ(loaded.gear.te_terms[i].order_output, g.te_terms[i].order_output);
  }
  EXPECT_DOUBLE_EQ(loaded.gear.backlash.total_rad, g.backlash.total_rad);
  const auto& k = std::get<model::ThreeSegmentStiffness>(loaded.gear.stiffness.law);
  const auto& k0 = std::get<model::ThreeSegmentStiffness>(g.stiffness.law);
  EXPECT_DOUBLE_EQ(k.k1, k0.k1);
  EXPECT_DOUBLE_EQ(k.k2, k0.k2);
  EXPECT_DOUBLE_EQ(k.t2, k0.t2);
  // And the twin built from the file predicts what the calibration's replay predicted.
  const auto& run = calibration_run();
  const std::span<const storage::SyncSample> first(run.samples.data(), 300);
  // The latch delay is the bench's, not the gear's: it comes with the solver options.
  const auto again = replay_twin(loaded.gear, testing::sense_of(loaded.gear), first, cal.solver);
  const auto direct = replay_twin(cal.calibrated, testing::sense_of(g), first, cal.solver);
  ASSERT_EQ(again.size(), direct.size());
  for (std::size_t i = 0; i < again.size(); ++i) {
    EXPECT_NEAR(again[i].predicted_te_rad, direct[i].predicted_te_rad, 1e-12) << i;
  }
}

TEST(TwinCalibration, StaticRunEstimateSeedsBacklashAndStiffness) {
  // A static result whose lost motion and load shift say: backlash 1 arcmin, 20 N*m twists
  // the true unit by x(20) = 20 / 6.7e4.
  metrology::StaticTeResult st;
  metrology::LostMotionProfile lm;
  lm.load_nm = 0;
  lm.mean_arcmin = 1.0;
  st.lost_motion.push_back(lm);
  metrology::LoadShift shift;
  shift.load_nm = 20;
  shift.reference_load_nm = 0;
  shift.shift_arcmin = 20 / 6.7e4 / kArcmin;
  st.load_shifts.push_back(shift);
  TwinCalibrationOptions options;
  options.passes = 0;  // the estimate alone
  const auto& run = calibration_run();
  const std::span<const storage::SyncSample> part(run.samples.data(), 2000);
  const auto cal = calibrate_twin(testing::nominal_gear(),
                                  testing::sense_of(testing::nominal_gear()), part, &st, options);
  EXPECT_NEAR(cal.calibrated.backlash.total_rad / kArcmin, 1.0, 1e-9);
  EXPECT_NEAR(cal.stiffness_factor, 6.7 / 5.0, 1e-3);
  EXPECT_EQ(cal.fitted.front(), "static_estimate");
}

}  // namespace
}  // namespace wavebench::twin

namespace wavebench::twin {
namespace {

TEST(TwinCalibration, AnEncoderZeroOffsetBecomesATeOffsetNotATwist) {
  // The output encoder's zero is arbitrary on a bench (here 0.01 rad, 34 arcmin): the twin
  // must not read it as a twist, the calibration fits it as a TE offset.
  const auto& run = calibration_run();
  std::vector<storage::SyncSample> samples(run.samples.begin(), run.samples.begin() + 5200);
  const double offset = 0.01;
  for (auto& s : samples) s.theta_out_rad += offset;
  const auto gear = testing::true_gear();
  const auto points = replay_twin(gear, testing::sense_of(gear), samples);
  for (std::size_t i = 0; i < points.size(); i += 500) {
    EXPECT_NEAR(points[i].predicted_te_rad, run.true_te_rad[i], 5 * testing::kArcsec) << i;
  }
  const auto cal = calibrate_twin(gear, testing::sense_of(gear), samples);
  EXPECT_NEAR(cal.before.mean_arcsec, offset / testing::kArcsec, 1.0);
  EXPECT_LE(cal.after.rms_arcsec, 1.1 * run.noise_floor_arcsec);
  EXPECT_EQ(std::find(cal.fitted.begin(), cal.fitted.end(), "stiffness"), cal.fitted.end());
  EXPECT_DOUBLE_EQ(cal.stiffness_factor, 1.0);
}

}  // namespace
}  // namespace wavebench::twin
