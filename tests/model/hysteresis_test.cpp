// Hysteretic stiffness forms 5-7 (model.md §4) under a periodic twist: the loops close, and the
// loop area equals the energy the model's loss account integrates over a period.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "gear_test_support.hpp"

namespace wavebench::model {
namespace {

using testing::kArcsec;

struct LoopCheck {
  double area = 0;        // closed integral of T dx over the last period
  double dissipated = 0;  // loss account over the same period
  double closure = 0;     // max |T(t) - T(t - P)| over the last period
  double torque_peak = 0;
  std::int64_t events = 0;
};

// The output is held by a huge inertia and the input turns at 50 rev/s, so a TE line of
// order 1 imposes the twist Delta = -X sin(2 pi 50 t) exactly.
LoopCheck run_loop(StiffnessLaw law, double amplitude, int periods) {
  const double f = 50, rate = 100000;
  GearParams p = testing::bare_gear(100, 1e-3, 1e12, 1.0);
  p.stiffness.law = std::move(law);
  p.input = KinematicInput{2 * std::numbers::pi * f, 0, {}, {}};
  p.te_terms = {{"drive", TeFamily::kCustom, amplitude, 1, 0, 0}};
  const GearModel model(p);
  const StateLayout& L = model.layout();
  std::vector<double> y(L.size, 0.0);
  const double period = 1 / f;
  const testing::GearRun run = testing::run_gear(model, y, periods * period, rate, 1e-10, 1e-12);
  const auto per = static_cast<std::size_t>(std::lround(rate * period));
  const std::size_t n = run.samples.size();
  LoopCheck c;
  c.events = static_cast<std::int64_t>(run.result.events.size());
  const std::size_t first = n - 1 - per;
  for (std::size_t i = first; i + 1 < n; ++i) {
    const auto& a = run.samples[i].out;
    const auto& b = run.samples[i + 1].out;
    c.area += 0.5 * (a.spring_torque + b.spring_torque) * (b.spring_twist - a.spring_twist);
    c.closure =
        std::max(c.closure, std::abs(a.spring_torque - run.samples[i - per].out.spring_torque));
    c.torque_peak = std::max(c.torque_peak, std::abs(a.spring_torque));
  }
  c.dissipated =
      run.samples[n - 1].y[L.dissipated_energy] - run.samples[first].y[L.dissipated_energy];
  return c;
}

TEST(Hysteresis, BranchFormLoopClosesAndAreaIsDissipation) {
  // Seed 001's form: loading K2 = A2 x^2 + B2 x + C2, unloading K1 stiffer, x in arcsec.
  const HystereticBranchStiffness law{1e-4, 1e-3, 0.5, 1e-4, 1e-3, 0.8};
  const LoopCheck c = run_loop(law, 60 * kArcsec, 20);
  EXPECT_GT(c.area, 1e-3 * c.torque_peak * 120 * kArcsec);  // a real loop
  EXPECT_LT(c.closure, 1e-3 * c.torque_peak);
  EXPECT_NEAR(c.dissipated / c.area, 1.0, 0.01);
  // Two reversals and two torque zero crossings per period.
  EXPECT_GE(c.events, 4 * 19);
}

TEST(Hysteresis, BranchFormTorqueFollowsTheClosedFormBranches) {
  // Virgin loading from zero: T = integral of K2 from 0, i.e. A2|x|^3/3 + B2 x^2/2 + C2|x|.
  const HystereticBranchStiffness law{1e-4, 1e-3, 0.5, 2e-4, 2e-3, 0.9};
  const HystereticBranchSpring spring(law);
  const double x = 40 * kArcsec;
  EXPECT_NEAR(spring.torque(x, {}), 1e-4 * 64000 / 3 + 1e-3 * 800 + 0.5 * 40, 1e-9);
  EXPECT_NEAR(spring.torque(-x, {}), -spring.torque(x, {}), 1e-12);
  // After a reversal at x the unloading branch starts at that point.
  const BranchAnchor a{x, spring.torque(x, {}), false};
  const double x2 = 10 * kArcsec;
  EXPECT_NEAR(spring.torque(x2, a),
              a.torque - (2e-4 * (64000 - 1000) / 3 + 2e-3 * (1600 - 100) / 2 + 0.9 * 30), 1e-9);
}

TEST(Hysteresis, FadingMemoryLoopClosesAndAreaIsDissipation) {
  // Seed 003's values; z' = A x' - B z.
  const FadingMemoryStiffness law{0.12, 0.56, 52000, 40000, 300};
  const LoopCheck c = run_loop(law, 1e-3, 12);
  EXPECT_GT(c.area, 1e-3 * c.torque_peak * 2e-3);
  EXPECT_LT(c.closure, 1e-6 * c.torque_peak);
  EXPECT_NEAR(c.dissipated / c.area, 1.0, 0.01);
  // Closed form for the memory part: z = A X w / sqrt(B^2 + w^2) sin(...), area pi X^2 A B w /
  // (B^2 + w^2) (the polynomial part stores and returns its energy).
  const double w = 2 * std::numbers::pi * 50, X = 1e-3;
  EXPECT_NEAR(c.area / (std::numbers::pi * X * X * 40000 * 300 * w / (300 * 300 + w * w)), 1.0,
              1e-3);
}

TEST(Hysteresis, BoucWenLoopClosesAndAreaIsDissipation) {
  for (double n : {1.0, 2.0}) {
    const double X = 1e-3;
    BoucWenStiffness law{1e5, 0.4, 0, 0, n};
    law.beta = 0.5 * std::pow(2 / X, n);  // ultimate |w| = (beta + gamma)^(-1/n) = X/2
    law.gamma = 0.5 * std::pow(2 / X, n);
    const LoopCheck c = run_loop(law, X, 12);
    EXPECT_GT(c.area, 0.05 * c.torque_peak * 2 * X) << n;
    EXPECT_LT(c.closure, 1e-4 * c.torque_peak) << n;
    EXPECT_NEAR(c.dissipated / c.area, 1.0, 0.01) << n;
  }
}

}  // namespace
}  // namespace wavebench::model
