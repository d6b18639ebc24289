// Backlash dead zone (model.md §5): the sharp zone transmits nothing, the smoothed form is odd,
// continuous and C1, and contact loss / impact are located as events.
#include "wavebench/model/backlash.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <numbers>

#include "gear_test_support.hpp"

namespace wavebench::model {
namespace {

using testing::kArcsec;

// Largest jump of a dead-zone function across the zone edges +-b/2, each side approached from
// its own branch; a correct form has none.
double edge_jump(const std::function<double(double)>& g, double b) {
  const double h = 1e-9 * b;
  double worst = 0;
  for (double edge : {-0.5 * b, 0.5 * b}) {
    worst = std::max(worst, std::abs(g(edge + h) - g(edge - h)));
  }
  return worst;
}

TEST(Backlash, SharpZoneFollowsTheSingleRule) {
  const double b = 8 * 60 * kArcsec;
  const BacklashDeadZone z(BacklashParams{b, 0});
  EXPECT_EQ(z.evaluate(0.3 * b).x, 0.0);
  EXPECT_EQ(z.evaluate(-0.5 * b).x, 0.0);
  EXPECT_DOUBLE_EQ(z.evaluate(0.8 * b).x, 0.3 * b);
  EXPECT_DOUBLE_EQ(z.evaluate(-0.8 * b).x, -0.3 * b);
  EXPECT_EQ(z.evaluate(0.8 * b).slope, 1.0);
  EXPECT_EQ(z.evaluate(0.2 * b).slope, 0.0);
}

TEST(Backlash, SmoothedFormIsOddContinuousAndC1) {
  const double b = 1e-3, eps = 2e-4;
  const BacklashDeadZone z(BacklashParams{b, eps});
  const double h = 1e-9;
  double prev_slope = z.evaluate(-b).slope;
  for (double x = -b; x <= b; x += 1e-7) {
    const DeadZoneValue v = z.evaluate(x);
    EXPECT_EQ(z.evaluate(-x).x, -v.x) << x;                 // odd
    EXPECT_LT(std::abs(z.evaluate(x + h).x - v.x), 2 * h);  // continuous (Lipschitz 1)
    const double fd = (z.evaluate(x + h).x - z.evaluate(x - h).x) / (2 * h);
    EXPECT_NEAR(fd, v.slope, 1e-5) << x;                                // slope is the derivative
    EXPECT_LT(std::abs(v.slope - prev_slope), 1e-7 / eps * 1.01) << x;  // slope continuous
    prev_slope = v.slope;
  }
  // Equal to the sharp form outside the blending band.
  EXPECT_DOUBLE_EQ(z.evaluate(0.5 * b + 0.6 * eps).x, 0.6 * eps);
  EXPECT_EQ(z.evaluate(0.5 * b - 0.6 * eps).x, 0.0);
  EXPECT_LT(edge_jump([&](double x) { return z.evaluate(x).x; }, b), 2.1e-9 * b);
}

TEST(Backlash, EdgeCheckCatchesSeed000Cubic) {
  // Seed 000's smoothing: at x = +delta/2 it gives -delta/2 where the outer branch gives 0.
  const double d = 1e-3;
  auto seed000 = [d](double x) {
    if (x >= d / 2) return x - d / 2;
    if (x <= -d / 2) return x + d / 2;
    const double s = x + d / 2;
    return s * s * s / (d * d) - 1.5 / d * s * s;
  };
  EXPECT_NEAR(seed000(d / 2 - 1e-15), -d / 2, 1e-12);
  EXPECT_GT(edge_jump(seed000, d), 0.4 * d);
  const BacklashDeadZone ours(BacklashParams{d, 0.5 * d});
  EXPECT_LT(edge_jump([&](double x) { return ours.evaluate(x).x; }, d), 1e-9 * d);
}

TEST(Backlash, NoTorqueInsideTheZoneAndNoPullingTorque) {
  const double b = 4 * 60 * kArcsec;
  GearParams p = testing::bare_gear(100, 1e-3, 0.5, 1e5);
  p.backlash.total_rad = b;
  p.damping.coefficient = 50;
  const GearModel model(p);
  const StateLayout& L = model.layout();
  std::vector<double> y(L.size, 0.0), d;
  for (double q : {-0.49 * b, -0.2 * b, 0.0, 0.3 * b, 0.499 * b}) {
    for (double r : {-1.0, 0.0, 2.0}) {
      y[L.twist] = q;
      y[L.twist_rate] = r;
      const GearOutputs o = model.outputs(0.0, y, d);
      EXPECT_EQ(o.gear_torque, 0.0) << q << " " << r;
      EXPECT_EQ(o.alpha2, 0.0);
    }
  }
  // In contact on the upper flank: separating fast, damping would pull; the torque stays >= 0.
  y[L.twist] = 0.5 * b + 1e-5;
  y[L.twist_rate] = -10;
  EXPECT_EQ(model.outputs(0.0, y, d).gear_torque, 0.0);
  // Closing fast: the damping part is capped at the spring part.
  y[L.twist_rate] = 10;
  const GearOutputs o = model.outputs(0.0, y, d);
  EXPECT_NEAR(o.gear_torque, 2 * 1e5 * 1e-5, 1e-9);
  // Slowly: spring plus damping.
  y[L.twist_rate] = 1e-3;
  EXPECT_NEAR(model.outputs(0.0, y, d).gear_torque, 1e5 * 1e-5 + 50 * 1e-3, 1e-9);
}

TEST(Backlash, ContactLossAndImpactAreLocated) {
  // Input held still (kinematic, speed 0), output released from a twisted contact: the twist
  // x = q - b/2 follows x0 cos(w t) with w = sqrt(k/J2) until contact is lost at pi/(2w), then
  // the output flies across the clearance at x0 w and hits the other flank b/(x0 w) later.
  const double b = 2 * 60 * kArcsec, k = 1e5, j2 = 0.5, x0 = 1e-4;
  GearParams p = testing::bare_gear(100, 1e-3, j2, k);
  p.backlash.total_rad = b;
  p.input = KinematicInput{0.0, 0, {}, {}};
  const GearModel model(p);
  const StateLayout& L = model.layout();
  std::vector<double> y(L.size, 0.0);
  y[L.twist] = 0.5 * b + x0;
  const double w = std::sqrt(k / j2);
  const double t_lost = std::numbers::pi / (2 * w);
  const double t_hit = t_lost + b / (x0 * w);
  const testing::GearRun run =
      testing::run_gear(model, y, t_hit + 0.5 * t_lost, 1000, 1e-10, 1e-12);
  ASSERT_GE(run.result.events.size(), 2u);
  const auto& lost = run.result.events[0];
  const auto& hit = run.result.events[1];
  EXPECT_EQ(model.event_kind(lost.witness, lost.direction), "contact_lost");
  EXPECT_EQ(model.event_kind(hit.witness, hit.direction), "contact_made");
  EXPECT_NEAR(lost.t, t_lost, 1e-9 * t_lost);
  EXPECT_NEAR(hit.t, t_hit, 1e-8 * t_hit);
  EXPECT_EQ(static_cast<int>(hit.witness), L.witness_lower_flank);
}

TEST(Backlash, SimulateListsContactEvents) {
  const double b = 2 * 60 * kArcsec;
  GearParams p = testing::bare_gear(100, 1e-3, 0.5, 1e5);
  p.backlash.total_rad = b;
  p.input = KinematicInput{0.0, 0, {}, {}};
  p.load.output_torque = {0.0, 5.0, 20.0, 0.0};  // alternating load drives flank to flank
  SimulationOptions o;
  o.t_end = 0.2;
  o.sample_rate = 1000;
  const SimulationResult r = simulate(p, o);
  int made = 0, lost = 0;
  for (const auto& e : r.events) {
    made += e.kind == "contact_made";
    lost += e.kind == "contact_lost";
  }
  EXPECT_GE(made, 2);
  EXPECT_GE(lost, 2);
  EXPECT_EQ(r.stats.events, static_cast<std::int64_t>(r.events.size()));
}

}  // namespace
}  // namespace wavebench::model
