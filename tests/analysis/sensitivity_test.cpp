// TE sensitivity and Monte-Carlo with the linear transfer function against closed forms.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "wavebench/analysis/te_sensitivity.hpp"

namespace wa = wavebench::analysis;
namespace wm = wavebench::model;

namespace {

wm::TeTerm term(const std::string& name, double amp, double a, double b, double phase) {
  wm::TeTerm t;
  t.source = name;
  t.amplitude_rad = amp;
  t.order_input = a;
  t.order_output = b;
  t.phase_rad = phase;
  return t;
}

wa::LinearGearCoefficients rigid_output() {
  wa::LinearGearCoefficients co;
  co.inertia_output = 1e-3;
  co.inertia_input = 1e-4;
  co.ratio = 100;
  co.stiffness = 1e9;  // far above the excitation: the output follows the TE
  co.input_prescribed = true;
  return co;
}

}  // namespace

TEST(TeSensitivity, LinearRmsOfTonesAddsInPowerAcrossFrequenciesAndAsPhasorsWithin) {
  wm::GearGeometry g;
  g.ratio = 100;
  const double speed = 2 * std::numbers::pi * 10;  // f_H = 10 Hz
  const auto co = rigid_output();
  const std::vector<wm::TeTerm> two_lines{term("a", 3e-6, 1, 0, 0), term("b", 4e-6, 2, 0, 1)};
  EXPECT_NEAR(wa::linear_rms(two_lines, g, speed, co, "theta2_dev"), 5e-6 / std::sqrt(2.0), 1e-10);
  const std::vector<wm::TeTerm> same_line{term("a", 3e-6, 2, 0, 0),
                                          term("b", 4e-6, 2, 0, std::numbers::pi)};
  EXPECT_NEAR(wa::linear_rms(same_line, g, speed, co, "theta2_dev"), 1e-6 / std::sqrt(2.0), 1e-10);
  // alpha2 of a tone A sin(w t) has amplitude A w^2.
  const double w = 2 * std::numbers::pi * 10;
  const std::vector<wm::TeTerm> one{term("a", 2e-6, 1, 0, 0)};
  EXPECT_NEAR(wa::linear_rms(one, g, speed, co, "alpha2"), 2e-6 * w * w / std::sqrt(2.0),
              1e-6 * 2e-6 * w * w);
}

TEST(TeSensitivity, MonteCarloOfOneTermHasTheUniformDistributionsMoments) {
  wm::GearGeometry g;
  g.ratio = 100;
  const auto co = rigid_output();
  const std::vector<wm::TeTerm> one{term("a", 2e-6, 1, 0, 0)};
  const auto mc = wa::monte_carlo_linear(one, g, 20.0, co, "theta2_dev", 20000, 7);
  const double nominal = 2e-6 / std::sqrt(2.0);
  EXPECT_NEAR(mc.nominal, nominal, 1e-12);
  // RMS = U nominal with U uniform on [0, 1]: mean 1/2, p95 0.95.
  EXPECT_NEAR(mc.mean / nominal, 0.5, 0.01);
  EXPECT_NEAR(mc.p95 / nominal, 0.95, 0.01);
  EXPECT_NEAR(mc.stddev / nominal, 1 / std::sqrt(12.0), 0.01);
  const auto again = wa::monte_carlo_linear(one, g, 20.0, co, "theta2_dev", 20000, 7);
  EXPECT_DOUBLE_EQ(again.p95, mc.p95);  // seeded: reproducible
}

TEST(TeSensitivity, LinearSensitivityRanksSourcesWithoutSimulating) {
  wm::GearParams p;
  p.geometry.ratio = 100;
  p.te_terms = {term("small", 1e-6, 1, 0, 0), term("large", 5e-6, 2, 0, 0),
                term("zero", 0, 3, 0, 0)};
  wa::SensitivityOptions o;
  o.relative_step = 0.01;
  o.monte_carlo_runs = 100;
  const auto s = wa::te_sensitivity(p, {}, o, "theta2_dev", 2 * std::numbers::pi * 10,
                                    rigid_output(), 0, false);
  ASSERT_EQ(s.sources.size(), 2u);
  EXPECT_EQ(s.sources[0].source, "large");
  EXPECT_TRUE(std::isnan(s.sources[0].finite_difference));
  // d RMS / d A * A for RMS = sqrt(A1^2 + A2^2)/sqrt 2: A2^2 / (sqrt 2 sqrt(A1^2 + A2^2)).
  const double exact = 25e-12 / (std::sqrt(2.0) * std::sqrt(26e-12));
  EXPECT_NEAR(s.sources[0].linear, exact, 0.01 * exact);
  EXPECT_EQ(s.monte_carlo.runs, 100);
  EXPECT_EQ(s.method, "linear transfer function");
}
