#include "wavebench/metrology/twin_calibration.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <numbers>

namespace wavebench::metrology {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kArcsec = kPi / 180 / 3600;
constexpr double kN = 80;

struct Term {
  double a, b, amplitude, phase;
};

double te(const std::vector<Term>& terms, double offset, double th1, double th2) {
  double e = offset;
  for (const auto& t : terms) e += t.amplitude * std::sin(t.a * th1 + t.b * th2 + t.phase);
  return e;
}

TEST(TwinCalibration, HarmonicFitRecoversAmplitudesPhasesAndTheResidualFalls) {
  const std::vector<Term> truth = {
      {2, 2, 20 * kArcsec, 0.3}, {0, 1, 10 * kArcsec, -1.0}, {1, 0, 4 * kArcsec, 2.5}};
  const std::vector<Term> nominal = {
      {2, 2, 14 * kArcsec, 0.0}, {0, 1, 0, 0}, {1, 0, 4 * kArcsec, 2.5}};
  const std::vector<HarmonicOrder> orders = {
      {"dF_i1", 2, 2}, {"output 1/rev", 0, 1}, {"wave generator", 1, 0}};
  std::vector<double> t, th1, th2, measured, predicted;
  for (int i = 0; i < 48000; ++i) {  // one output revolution at 100 rpm, 1 kHz
    const double time = 1e-3 * i;
    const double a1 = 100.0 / 60 * 2 * kPi * time;
    t.push_back(time);
    th1.push_back(a1);
    th2.push_back(a1 / kN);
    measured.push_back(te(truth, 15 * kArcsec, a1, a1 / kN));
    predicted.push_back(te(nominal, 0, a1, a1 / kN));
  }
  const auto fit = fit_te_harmonics(th1, th2, measured, orders);
  EXPECT_NEAR(fit.offset_rad, 15 * kArcsec, 1e-12);
  ASSERT_EQ(fit.harmonics.size(), 3u);
  for (std::size_t j = 0; j < 3; ++j) {
    EXPECT_NEAR(fit.harmonics[j].amplitude_rad, truth[j].amplitude, 1e-12) << j;
    EXPECT_NEAR(fit.harmonics[j].phase_rad, truth[j].phase, 1e-9) << j;
  }
  EXPECT_LT(fit.rms_residual_rad, 1e-13);

  const auto before = twin_residual(measured, predicted);
  // Residual before: offset 15" plus three sines; over one output revolution they are
  // orthogonal, so RMS² = 15² + Σ|ΔA|²/2 with ΔA the phasor differences.
  const double d1 = std::abs(std::polar(20.0, 0.3) - std::polar(14.0, 0.0));
  EXPECT_NEAR(before.rms_arcsec, std::sqrt(15 * 15 + (d1 * d1 + 10 * 10) / 2), 1e-3);
  std::vector<double> calibrated;
  for (std::size_t i = 0; i < t.size(); ++i) calibrated.push_back(fit.evaluate(th1[i], th2[i]));
  const auto after = twin_residual(measured, calibrated);
  EXPECT_LT(after.rms_arcsec, 1e-6);
  EXPECT_LT(after.rms_arcsec, 1e-6 * before.rms_arcsec);
  EXPECT_EQ(to_json(fit)["terms"].size(), 3u);
}

TEST(TwinCalibration, RepeatedOrderIsRejected) {
  const std::vector<double> x(10, 0.0);
  const std::vector<HarmonicOrder> orders = {{"a", 2, 2}, {"b", 2, 2}};
  EXPECT_THROW(fit_te_harmonics(x, x, x, orders), std::invalid_argument);
}

TEST(TwinCalibration, StiffnessAndBacklashFromTheLoadedAndUnloadedShift) {
  const GearSense sense{80, 1};
  const double k = 4.2e4, backlash_arcmin = 0.3;
  const double shift_arcmin = 60 / k * 180 / kPi * 60;
  auto pass = [&](Direction d, double load, double mean) {
    StaticTePass p;
    p.direction = d;
    p.load_nm = load;
    for (int i = 0; i < 24; ++i) {
      const double theta2 = 2 * kPi * i / 24;
      const double te_rad = (mean + std::sin(theta2)) / (180 / kPi * 60);
      p.points.push_back({i, kN * (theta2 - te_rad), theta2, load});
    }
    return p;
  };
  const std::vector<StaticTePass> passes = {
      pass(Direction::kForward, 0, -1.6), pass(Direction::kReverse, 0, -1.6 - backlash_arcmin),
      pass(Direction::kForward, 60, -1.6 + shift_arcmin),
      pass(Direction::kReverse, 60, -1.6 - backlash_arcmin + shift_arcmin)};
  const auto e = estimate_stiffness_backlash(analyse_static_te(passes, sense));
  EXPECT_NEAR(e.backlash_rad * 180 / kPi * 60, backlash_arcmin, 1e-9);
  EXPECT_NEAR(e.stiffness_nm_per_rad, k, 1e-6 * k);
  EXPECT_EQ(e.load_nm, 60);
}

}  // namespace
}  // namespace wavebench::metrology
