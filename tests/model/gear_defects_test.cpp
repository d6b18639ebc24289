// The simulated unit's defects (gear_defects.hpp) against closed forms: where a damaged tooth
// meshes, in which angle its pulse repeats, which orders of the output revolution its pulse
// train holds, and the rising 1/rev's growth with the revolutions turned.
#include "wavebench/model/gear_defects.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <numbers>

#include "wavebench/model/gear_model.hpp"

namespace wavebench::model {
namespace {

constexpr double kPi = std::numbers::pi;

GearGeometry geometry() {
  return {200, 202, 2, 100.0, 1};  // N = 100, U = 2
}

GearDefects one_tooth(DefectPart part, int tooth = 17, double width = 0.25) {
  GearDefects d;
  d.teeth.push_back({part, tooth, 1e-4, width, 0});
  return d;
}

double value(const GearDefects& d, double theta1, double theta2, double travel = 0) {
  return defect_excitation(d, geometry(), theta1, theta2, 0, 0, travel).value;
}

// Amplitude of output order k of the pulse train over one output revolution (θ1 = N θ2).
double output_order_line(const GearDefects& d, int k) {
  const int m = 40000;
  std::complex<double> sum = 0;
  for (int i = 0; i < m; ++i) {
    const double theta2 = 2 * kPi * i / m;
    sum += value(d, 100 * theta2, theta2) * std::polar(1.0, -k * theta2);
  }
  return 2 * std::abs(sum) / m;
}

TEST(ToothDefect, AFlexsplineToothPeaksWhereALobeMeetsItAndRepeatsInTheRelativeAngle) {
  const auto d = one_tooth(DefectPart::kFlexspline);
  const double tooth = 2 * kPi * 17 / 200;
  // Lobe m of U = 2 meets the tooth where θ1 + θ2 = tooth angle + m π.
  EXPECT_NEAR(value(d, tooth - 0.3, 0.3), 1e-4, 1e-15);
  EXPECT_NEAR(value(d, tooth - 0.3 + kPi, 0.3), 1e-4, 1e-15);
  // Periodic in θ1 + θ2 (period π), not in θ1 alone.
  EXPECT_NEAR(value(d, 1.234, 0.05), value(d, 1.234 + kPi - 0.01, 0.06), 1e-15);
  // Zero outside its width: a quarter of the π between meshes, centred on the tooth.
  EXPECT_EQ(value(d, tooth + 0.126 * kPi, 0), 0.0);
  EXPECT_GT(value(d, tooth + 0.124 * kPi, 0), 0.0);
}

TEST(ToothDefect, ACircularSplineToothIsFixedSoItRepeatsInTheInputAngleAlone) {
  const auto d = one_tooth(DefectPart::kCircularSpline);
  const double tooth = 2 * kPi * 17 / 202;
  EXPECT_NEAR(value(d, tooth, 0.7), 1e-4, 1e-15);
  EXPECT_NEAR(value(d, tooth + kPi, -2.0), 1e-4, 1e-15);
  EXPECT_NEAR(value(d, 0.4, 0.1), value(d, 0.4 + kPi, 1.3), 1e-15);
}

TEST(ToothDefect, ItsLinesSitAtMultiplesOfUTimesNPlusOneForTheFlexsplineAndUTimesNForTheCircular) {
  const auto flex = one_tooth(DefectPart::kFlexspline);
  const auto circ = one_tooth(DefectPart::kCircularSpline);
  // Raised-cosine pulse train: c_k = A w sinc(k w) / (1 − (k w)²), w = 0.25.
  const auto c = [](int k) {
    const double x = 0.25 * k;
    return 1e-4 * 0.25 * std::sin(kPi * x) / (kPi * x) / (1 - x * x);
  };
  EXPECT_NEAR(output_order_line(flex, 202), c(1), 1e-3 * c(1));
  EXPECT_NEAR(output_order_line(flex, 404), c(2), 1e-3 * c(1));
  EXPECT_NEAR(output_order_line(circ, 200), c(1), 1e-3 * c(1));
  EXPECT_NEAR(output_order_line(circ, 400), c(2), 1e-3 * c(1));
  for (int k : {1, 2, 100, 200, 201, 203, 303}) {
    EXPECT_LT(output_order_line(flex, k), 1e-3 * c(1)) << "Flexspline, order " << k;
  }
  for (int k : {1, 2, 101, 199, 201, 202, 300}) {
    EXPECT_LT(output_order_line(circ, k), 1e-3 * c(1)) << "Circular Spline, order " << k;
  }
}

TEST(ToothDefect, ItsRateIsTheDerivativeAlongTheMotion) {
  const auto d = one_tooth(DefectPart::kFlexspline, 5, 0.4);
  const double w1 = 30, w2 = 0.3, h = 1e-7;
  for (double t : {0.0001, 0.0023, 0.0051, 0.0102}) {
    const auto at = [&](double s) { return value(d, w1 * s, w2 * s); };
    const double numeric = (at(t + h) - at(t - h)) / (2 * h);
    const double rate = defect_excitation(d, geometry(), w1 * t, w2 * t, w1, w2, 0).rate;
    EXPECT_NEAR(rate, numeric, 1e-6 * std::abs(numeric) + 1e-9) << "t = " << t;
  }
}

TEST(ToothDefect, NothingBeforeItsOnset) {
  auto d = one_tooth(DefectPart::kFlexspline, 0);
  d.teeth[0].onset_rev = 3;
  EXPECT_EQ(value(d, 0, 0, 2.99), 0.0);
  EXPECT_NEAR(value(d, 0, 0, 3.0), 1e-4, 1e-15);
}

TEST(RisingOncePerRev, GrowsLinearlyWithTheRevolutionsTurnedAfterOnset) {
  GearDefects d;
  d.rising_once_per_rev.push_back({2e-5, 0.5, 1.0});
  const double theta2 = 1.1;
  EXPECT_EQ(value(d, 0, theta2, 0.5), 0.0);
  EXPECT_NEAR(value(d, 0, theta2, 3.0), 2 * 2e-5 * std::sin(theta2 + 0.5), 1e-15);
  EXPECT_NEAR(value(d, 0, theta2, 5.0), 4 * 2e-5 * std::sin(theta2 + 0.5), 1e-15);
  // e' = A ω2 cos(θ2 + φ) + (dA/drev) |ω2| / 2π sin(θ2 + φ).
  const auto r = defect_excitation(d, geometry(), 0, theta2, 0, 0.7, 3.0);
  EXPECT_NEAR(r.rate,
              4e-5 * 0.7 * std::cos(theta2 + 0.5) + 2e-5 * 0.7 / (2 * kPi) * std::sin(theta2 + 0.5),
              1e-15);
}

TEST(GearDefects, TheGearModelRefusesThem) {
  GearParams p;
  p.geometry = geometry();
  p.inertia_input = 1e-4;
  p.inertia_output = 0.05;
  p.stiffness.law = LinearPeriodicStiffness{3e4, {}};
  p.defects = one_tooth(DefectPart::kFlexspline);
  try {
    GearModel model(p);
    ADD_FAILURE() << "GearModel took a gear with defects";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("defects"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace wavebench::model
