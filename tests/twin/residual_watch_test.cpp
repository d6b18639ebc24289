// The twin's diagnosis (residual_watch.hpp) against synthetic residuals in closed form: a
// nominal twin of seed 004's unit predicts its TE lines, the "measured" TE is the unit's true
// lines (amplitudes ×1.08, phases +4°, as the simulated bench's unit), the sensors' noise and,
// where a test says so, a defect's pulse train (model::defect_excitation, a raised cosine per
// mesh of the damaged tooth) or a rising 1/rev. Rigid gear: TE = −e.
#include "wavebench/twin/residual_watch.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <filesystem>
#include <numbers>
#include <random>

#include "wavebench/config/twin_case.hpp"
#include "wavebench/model/gear_defects.hpp"

namespace wavebench::twin {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kArcsec = kPi / (180.0 * 3600.0);
constexpr double kArcmin = 60 * kArcsec;

model::GearParams nominal() {
  return config::load_twin_case(std::filesystem::path(WAVEBENCH_SOURCE_DIR) / "configs" / "twin" /
                                "bench-unit-seed004.yaml")
      .gear;
}

double excitation(const std::vector<model::TeTerm>& terms, double theta1, double theta2) {
  double e = 0;
  for (const auto& t : terms) {
    e += t.amplitude_rad * std::sin(t.order_input * theta1 + t.order_output * theta2 + t.phase_rad);
  }
  return e;
}

struct SyntheticRun {
  double seconds_per_revolution = 10;
  double sample_period_s = 1e-3;
  double noise_rad = 0.5 * kArcsec;
  model::GearDefects defects;
  double start_rev = 0;  // output revolutions turned before the run (defect onsets count them)
};

// Feeds `revolutions` output revolutions (plus a little) to a watch, sample by sample.
DiagnosticReport watch(const SyntheticRun& run, double revolutions,
                       ResidualWatchOptions options = {}) {
  const auto twin = nominal();
  auto truth = twin;
  for (auto& t : truth.te_terms) {
    t.amplitude_rad *= 1.08;
    t.phase_rad += 4 * kPi / 180;
  }
  const double n = twin.geometry.ratio;
  options.sensor_noise_rad = run.noise_rad;
  ResidualWatch w(twin, n, options);
  std::mt19937 rng(7);
  std::normal_distribution<double> noise(0, run.noise_rad);
  const double omega2 = 2 * kPi / run.seconds_per_revolution;
  const auto samples = static_cast<std::size_t>((revolutions + 0.01) * run.seconds_per_revolution /
                                                run.sample_period_s);
  for (std::size_t i = 0; i < samples; ++i) {
    const double t = static_cast<double>(i) * run.sample_period_s;
    TwinPoint p;
    p.index = i;
    p.t_s = t;
    p.theta2_rad = omega2 * t;
    p.theta1_rad = n * p.theta2_rad;
    const auto defect =
        model::defect_excitation(run.defects, twin.geometry, p.theta1_rad, p.theta2_rad, n * omega2,
                                 omega2, run.start_rev + p.theta2_rad / (2 * kPi));
    p.predicted_te_rad = -excitation(twin.te_terms, p.theta1_rad, p.theta2_rad);
    p.measured_te_rad =
        -excitation(truth.te_terms, p.theta1_rad, p.theta2_rad) - defect.value + noise(rng);
    w.feed(p);
  }
  return w.report();
}

model::ToothDefect tooth(model::DefectPart part, double onset_rev = 0) {
  model::ToothDefect d;
  d.part = part;
  d.tooth = 17;
  d.amplitude_rad = 0.5 * kArcmin;
  d.width = 0.25;
  d.onset_rev = onset_rev;
  return d;
}

TEST(ResidualWatch, FlexsplineToothIsFlaggedInTheFirstRevolutionAtOrderUTimesNPlusOne) {
  SyntheticRun run;
  run.defects.teeth = {tooth(model::DefectPart::kFlexspline)};
  const auto r = watch(run, 3);
  ASSERT_EQ(r.revolutions.size(), 3u);
  ASSERT_EQ(r.flags.size(), 1u);
  const auto& f = r.flags.front();
  std::printf("%s\n", describe(f).c_str());
  EXPECT_EQ(f.order, 202);  // U (N + 1), N = 100
  EXPECT_EQ(f.first_revolution, 1);
  EXPECT_EQ(f.revolutions, 3);
  ASSERT_FALSE(f.sources.empty());
  EXPECT_EQ(f.sources.front().family, "tangential_output");
  EXPECT_EQ(f.sources.front().harmonic, 1);
  // A raised-cosine pulse train: its harmonics sit at every multiple of the mesh order.
  ASSERT_GE(f.lines.size(), 2u);
  EXPECT_EQ(f.lines[1].order, 404);
  // Closed form of the fundamental: 2 · A · (w/2) · sinc(w) / (1 − w²), w = 0.25.
  const double w = 0.25;
  const double c1 = 0.5 * kArcmin * w * std::sin(kPi * w) / (kPi * w) / (1 - w * w);
  EXPECT_NEAR(f.lines[0].amplitude_rad, c1, 0.1 * c1 + 2 * kArcsec);
}

TEST(ResidualWatch, CircularSplineToothIsFlaggedAtOrderUTimesNWithTheFixedSplineRankedFirst) {
  SyntheticRun run;
  run.defects.teeth = {tooth(model::DefectPart::kCircularSpline)};
  const auto r = watch(run, 2);
  ASSERT_EQ(r.flags.size(), 1u);
  const auto& f = r.flags.front();
  std::printf("%s\n", describe(f).c_str());
  EXPECT_EQ(f.order, 200);  // U N
  EXPECT_EQ(f.first_revolution, 1);
  ASSERT_FALSE(f.sources.empty());
  EXPECT_EQ(f.sources.front().family, "tangential_fixed");
  EXPECT_NE(f.suspect.find("Circular Spline"), std::string::npos) << f.suspect;
}

TEST(ResidualWatch, AHealthyUnitOverTwentyRevolutionsRaisesNoFlag) {
  SyntheticRun run;
  const auto r = watch(run, 20);
  ASSERT_EQ(r.revolutions.size(), 20u);
  double largest = 0;
  for (const auto& v : r.revolutions) largest = std::max(largest, v.largest_ratio);
  std::printf("largest line over its band in 20 healthy revolutions: %.3f\n", largest);
  EXPECT_TRUE(r.flags.empty()) << describe(r.flags.front());
  EXPECT_LT(largest, 1.0);
}

TEST(ResidualWatch, ADefectAppearingMidRunIsFlaggedWithinTwoRevolutionsOfItsOnset) {
  SyntheticRun run;
  const double onset = 4.5;
  run.defects.teeth = {tooth(model::DefectPart::kFlexspline, onset)};
  const auto r = watch(run, 8);
  for (const auto& f : r.flags) std::printf("%s\n", describe(f).c_str());
  ASSERT_EQ(r.flags.size(), 1u);
  const auto& f = r.flags.front();
  EXPECT_EQ(f.order, 202);
  EXPECT_GT(f.first_revolution, static_cast<int>(onset));  // not before it
  EXPECT_LE(f.first_revolution, onset + 2);                // the revolution ends by onset + 2
  EXPECT_LE(f.first_t_s, (onset + 2) * run.seconds_per_revolution + 1e-6);
}

TEST(ResidualWatch, ARisingOncePerRevIsFlaggedWhenItLeavesItsBandWithTheOutputOnceRevFirst) {
  // A wearing bearing grows slowly (here 0.04' a revolution: within one revolution its ramp
  // spreads less than the sensor floor to the neighbouring orders). The residual's 1/rev is
  // the twin's mismatch (2.7' at 4° against 2.5' at 0°) plus the growth; its band is 0.25 of
  // the twin's own 2.5'. Closed form of the revolution where it leaves the band:
  SyntheticRun run;
  const double growth = 0.04 * kArcmin;
  run.defects.rising_once_per_rev = {{growth, 0.0, 0}};
  const std::complex<double> mismatch =
      std::polar(2.7 * kArcmin, 4 * kPi / 180) - std::complex<double>(2.5 * kArcmin, 0);
  int crossing = 0;
  for (int r = 1; r <= 30 && crossing == 0; ++r) {
    if (std::abs(mismatch + growth * (r - 0.5)) > 0.25 * 2.5 * kArcmin) crossing = r;
  }
  ASSERT_EQ(crossing, 11);
  const auto r = watch(run, 14);
  ASSERT_FALSE(r.flags.empty());
  const auto& f = r.flags.front();
  std::printf("%s\n", describe(f).c_str());
  EXPECT_EQ(r.flags.size(), 1u);
  EXPECT_EQ(f.order, 1);
  EXPECT_GE(f.first_revolution, crossing - 1);
  EXPECT_LE(f.first_revolution, crossing + 1);
  ASSERT_FALSE(f.sources.empty());
  EXPECT_EQ(f.sources.front().family, "output_once_rev");
  EXPECT_NE(f.suspect.find("bearing"), std::string::npos) << f.suspect;
}

TEST(ResidualWatch, AReversalStartsANewRevolutionAndStandstillAddsNothing) {
  const auto twin = nominal();
  ResidualWatch w(twin, 100);
  // Standing still for 1000 samples, then half a revolution forward and one back: no whole
  // revolution one way.
  std::uint64_t i = 0;
  const auto feed = [&](double theta1) {
    TwinPoint p;
    p.index = i;
    p.t_s = 1e-3 * static_cast<double>(i++);
    p.theta1_rad = theta1;
    p.measured_te_rad = p.predicted_te_rad = 0;
    w.feed(p);
  };
  for (int k = 0; k < 1000; ++k) feed(0);
  const double rev = 2 * kPi * 100;
  for (int k = 0; k <= 5000; ++k) feed(0.5 * rev * k / 5000);
  for (int k = 0; k <= 10000; ++k) feed(0.5 * rev - 0.99 * rev * k / 10000);
  EXPECT_TRUE(w.report().revolutions.empty());
  EXPECT_EQ(w.report().unsteady_revolutions, 0);
  for (int k = 0; k <= 2000; ++k) feed(-0.49 * rev - 0.02 * rev * k / 2000);
  // 0.5 → −0.51 rev: one whole one back.
  EXPECT_EQ(
      w.report().revolutions.size() + static_cast<std::size_t>(w.report().unsteady_revolutions),
      1u);
}

TEST(ResidualWatch, ARevolutionWithStopsLikeAStaticRunsIsNotAnalysed) {
  const auto twin = nominal();
  ResidualWatch w(twin, 100);
  // 24 moves per revolution, each followed by a dwell: one whole revolution forward.
  const double rev = 2 * kPi * 100;
  std::uint64_t i = 0;
  for (int position = 0; position < 25; ++position) {
    for (int k = 0; k < 400; ++k) {
      TwinPoint p;
      p.index = i;
      p.t_s = 1e-3 * static_cast<double>(i++);
      // 100 samples moving to the next position, 300 standing there.
      p.theta1_rad = rev / 24 * (position + std::min(1.0, k / 100.0));
      p.measured_te_rad = p.predicted_te_rad = 0;
      w.feed(p);
    }
  }
  EXPECT_TRUE(w.report().revolutions.empty());
  EXPECT_EQ(w.report().unsteady_revolutions, 1);
}

TEST(ResidualWatchBand, IsTheLargestOfFloorMedianAndTheTwinsOwnLine) {
  ResidualWatchOptions o;  // relative 0.25, floor × 1, median × 8
  // Bins 0..8; the median of bins 1..8 is 0.1 (8 × 0.1 = 0.8).
  const std::vector<double> residual = {9, 0.1, 0.1, 0.1, 5.0, 0.1, 0.7, 3.0, 0.1};
  const std::vector<double> predicted = {0, 0, 0, 0, 0, 0, 0, 20, 0};
  double largest = 0;
  int at = 0;
  const auto lines = lines_above_band(residual, predicted, 0.5, o, 8, &largest, &at);
  ASSERT_EQ(lines.size(), 1u);  // order 4 (5.0 > 0.8); 6 (0.7 < 0.8); 7 (3.0 < 0.25 · 20)
  EXPECT_EQ(lines[0].order, 4);
  EXPECT_DOUBLE_EQ(lines[0].band_rad, 0.8);
  EXPECT_EQ(at, 4);
  EXPECT_DOUBLE_EQ(largest, 5.0 / 0.8);
}

TEST(ResidualWatchBand, LinesGroupIntoHarmonicSeriesUpToMaxHarmonic) {
  std::vector<FlaggedLine> lines;
  for (int k : {606, 1, 202, 2, 200, 404, 400, 9}) lines.push_back({k, 1, 1, 0});
  const auto s = harmonic_series(lines, 8);
  ASSERT_EQ(s.size(), 4u);
  EXPECT_EQ(s[0].size(), 2u);  // 1, 2 (9 is the 9th harmonic of 1: beyond 8)
  EXPECT_EQ(s[1].front().order, 9);
  EXPECT_EQ(s[2].front().order, 200);
  EXPECT_EQ(s[2].back().order, 400);
  EXPECT_EQ(s[3].front().order, 202);
  EXPECT_EQ(s[3].size(), 3u);  // 202, 404, 606
}

TEST(ResidualWatchBand, SeriesAtOrdersTheTwinDoesNotKnowBesideAStrongerLineAreItsSidebands) {
  // The twin knows orders 202 and 200. A pulse train that appears mid-revolution: 202 strong
  // and flagged, its sidebands 199, 203, 205 flagged too; a sideband of an unflagged line
  // (230 beside 231) goes; 200, weaker than 202 but a known order, stays its own.
  std::vector<double> residual(260, 0.01);
  const std::vector<FlaggedLine> lines = {{202, 8, 1, 0},   {203, 2.5, 1, 0}, {199, 1, 1, 0},
                                          {205, 0.9, 1, 0}, {200, 3, 1, 0},   {230, 0.6, 0.5, 0}};
  for (const auto& l : lines) residual[static_cast<std::size_t>(l.order)] = l.amplitude_rad;
  residual[231] = 0.55;  // below its band, not flagged
  const auto s = attach_sidebands(harmonic_series(lines, 8), residual, {200, 202}, {});
  ASSERT_EQ(s.size(), 2u);
  EXPECT_EQ(s[0].front().order, 200);
  EXPECT_EQ(s[0].size(), 1u);
  EXPECT_EQ(s[1].front().order, 202);
  ASSERT_EQ(s[1].size(), 4u);  // 202, then its sidebands by order
  EXPECT_EQ(s[1][1].order, 199);
  EXPECT_EQ(s[1][3].order, 205);
}

TEST(ResidualWatchRanking, AnOrderWithoutATermIsRankedByTheTermsItIsAHarmonicOf) {
  const auto twin = nominal();
  const auto at_404 = rank_sources_at_order(twin, 100, 404, 8);
  ASSERT_FALSE(at_404.empty());
  EXPECT_EQ(at_404.front().family, "tangential_output");
  EXPECT_EQ(at_404.front().harmonic, 2);
  const auto at_202 = rank_sources_at_order(twin, 100, 202, 8);
  ASSERT_EQ(at_202.size(), 1u);
  EXPECT_DOUBLE_EQ(at_202.front().share, 1.0);
  // Order 200: dF_i2 (2, 0) at 0.15' before the Flexspline tooth pitch (0, 200) at 0.1'.
  const auto at_200 = rank_sources_at_order(twin, 100, 200, 8);
  ASSERT_EQ(at_200.size(), 2u);
  EXPECT_EQ(at_200.front().family, "tangential_fixed");
  EXPECT_NEAR(at_200.front().share, 0.6, 1e-9);
}

}  // namespace
}  // namespace wavebench::twin
