// TE excitation as a function of the shaft angles, and the TE sign convention (model.md §1, §3).
#include "wavebench/model/te_excitation.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "gear_test_support.hpp"
#include "wavebench/model/angle_phasor.hpp"

namespace wavebench::model {
namespace {

using testing::kArcsec;

TEST(TeExcitation, MatchesTheSumOfSinesAtLargeAngles) {
  const std::vector<TeTerm> terms = {
      {"wg", TeFamily::kWaveGenerator, 1 * kArcsec, 1, 0, 0.3},
      {"dF_i1", TeFamily::kTangentialOutput, 20 * kArcsec, 2, 2, 0.7},
      {"T1k_1", TeFamily::kOutputAssembly, 5 * kArcsec, 2, 2, -1.2},  // merged with dF_i1
      {"mesh", TeFamily::kToothMesh, 0.5 * kArcsec, 540, 0, 0.2},
      {"flange", TeFamily::kOutputOnceRev, 3 * kArcsec, 0, 1, 2.0},
      {"odd", TeFamily::kCustom, 2 * kArcsec, 1.5, -0.25, 0.1}};
  const TeExcitation te(terms);
  for (double theta1 : {0.0, 1.3, 561.2, 12345.6}) {
    const double theta2 = theta1 / 134 - 3e-4, w1 = 280.6, w2 = w1 / 134 + 0.01;
    double e = 0, rate = 0;
    for (const auto& t : terms) {
      const double arg = t.order_input * theta1 + t.order_output * theta2 + t.phase_rad;
      e += t.amplitude_rad * std::sin(arg);
      rate += t.amplitude_rad * (t.order_input * w1 + t.order_output * w2) * std::cos(arg);
    }
    const TeValue v = te.evaluate(theta1, theta2, w1, w2);
    EXPECT_NEAR(v.value, e, 1e-6 * kArcsec) << theta1;
    EXPECT_NEAR(v.rate, rate, 1e-6 * kArcsec * 540 * w1) << theta1;
  }
}

TEST(TeExcitation, UnitPhasorMatchesLibmToARounding) {
  // The inline sincos behind the TE lines, against libm over the angles a run reaches.
  double worst = 0;
  for (double x = -2e6; x < 2e6; x += 9.87654321) {
    const Phasor p = unit_phasor(x);
    worst = std::max({worst, std::abs(p.re - std::cos(x)), std::abs(p.im - std::sin(x))});
  }
  for (double x = -7; x < 7; x += 1e-4) {
    const Phasor p = unit_phasor(x);
    worst = std::max({worst, std::abs(p.re - std::cos(x)), std::abs(p.im - std::sin(x))});
  }
  EXPECT_LT(worst, 5e-16);
  const Phasor z = unit_power(unit_phasor(0.3), -540);
  EXPECT_NEAR(z.re, std::cos(-162.0), 1e-13);
  EXPECT_NEAR(z.im, std::sin(-162.0), 1e-13);
}

TEST(TeExcitation, LineFrequencyFollowsOrders) {
  GearGeometry g{268, 270, 2, 134, 1};
  const double w = 2680 * 2 * std::numbers::pi / 60;
  EXPECT_NEAR(te_term_frequency_hz({"", TeFamily::kTangentialOutput, 1, 2, 2, 0}, g, w),
              2 * (1 + 1.0 / 134) * 2680 / 60.0, 1e-9);
  EXPECT_NEAR(te_term_frequency_hz({"", TeFamily::kToothMesh, 1, 540, 0, 0}, g, w), 24120, 1e-9);
}

TEST(TeSign, OutputLagsUnderLoadSoTeIsNegative) {
  // TE = theta2 - theta1/N. A load opposing the output twists the gear: the output lags the
  // input, so TE = -(b/2 + T_L/k) at standstill of the transient.
  const double k = 1e5, b = 2 * 60 * kArcsec, load = 30;
  GearParams p = testing::bare_gear(134, 2.2e-4, 0.3, k);
  p.backlash.total_rad = b;
  p.damping.damping_ratio = 0.3;
  p.input = KinematicInput{100.0, 0, {}, {}};
  p.load.output_torque.offset = load;
  SimulationOptions o;
  o.t_end = 0.05;
  o.sample_rate = 1000;
  const SimulationResult r = simulate(p, o);
  const auto& s = r.response;
  const std::size_t last = s.t.size() - 1;
  EXPECT_NEAR(s.te[last], -(b / 2 + load / k), 1e-6 * kArcsec);
  EXPECT_NEAR(s.gear_torque[last], load, 1e-6);
  // The channel is theta2 - theta1/N: kinematic input, so theta1 is the nominal motion.
  EXPECT_DOUBLE_EQ(s.te[last], s.theta2_dev[last]);
  EXPECT_DOUBLE_EQ(s.theta1[last], 100.0 * s.t[last]);
  // Delta = theta1/N - theta2 - e with e = 0: the twist is -TE.
  EXPECT_DOUBLE_EQ(s.twist[last], -s.te[last]);
}

TEST(TeSign, RigidGearFollowsTheExcitationWithMinusSign) {
  // Stiff, well damped, slow: Delta stays ~0, so TE = theta2 - theta1/N = -e.
  const double amp = 20 * kArcsec;
  GearParams p = testing::bare_gear(50, 1e-3, 0.01, 1e7);
  p.damping.damping_ratio = 0.7;
  p.input = KinematicInput{1.0, 0, {}, {}};
  p.te_terms = {{"line", TeFamily::kCustom, amp, 2, 0, 0}};
  SimulationOptions o;
  o.t_end = 2.0;
  o.transient = 0.5;
  o.sample_rate = 100;
  const SimulationResult r = simulate(p, o);
  for (std::size_t i = 0; i < r.response.t.size(); ++i) {
    const double e = amp * std::sin(2 * r.response.theta1[i]);
    EXPECT_NEAR(r.response.te[i], -e, 1e-3 * amp);
  }
}

}  // namespace
}  // namespace wavebench::model
