// LuGre friction at the wave generator (model.md §6): stick-slip when a slowly moving spring
// drags the input, presliding hysteresis below breakaway, and no stall of the implicit solver
// for stiff bristles.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "gear_test_support.hpp"

namespace wavebench::model {
namespace {

// Astrom's stick-slip case (m = 1, k = 2, v = 0.1, Fc = 1, Fs = 1.5, vs = 1e-3, sigma2 = 0.4) as
// a gear of ratio 1: the input carries the friction, a flywheel output turning at v drags it
// through the gear spring.
struct StickSlip {
  int slips = 0;
  double peak_speed = 0;
  double stuck_time = 0;  // with |omega1| < 1e-3
  std::int64_t steps = 0;
};

StickSlip run_stick_slip(double sigma0, double t_end) {
  GearParams p = testing::bare_gear(1, 1.0, 1e9, 2.0);
  p.friction = LuGreFriction{sigma0, 2 * std::sqrt(sigma0), 0.4, 1.0, 1.5, 1e-3};
  const GearModel model(p);
  const StateLayout& L = model.layout();
  std::vector<double> y(L.size, 0.0);
  y[L.twist_rate] = -0.1;  // r = omega1/N - omega2 with omega2 = 0.1
  const testing::GearRun run =
      testing::run_gear(model, y, t_end, 200, 1e-6, 1e-6, solver::IntegratorKind::kRosenbrock);
  StickSlip s;
  s.steps = run.result.counters.steps;
  bool slipping = false;
  for (const auto& smp : run.samples) {
    const double w = smp.out.omega1;
    s.peak_speed = std::max(s.peak_speed, w);
    if (!slipping && w > 0.05) {
      slipping = true;
      ++s.slips;
    } else if (slipping && std::abs(w) < 1e-3) {
      slipping = false;
    }
    if (std::abs(w) < 1e-3) s.stuck_time += 1.0 / 200;
  }
  return s;
}

TEST(LuGre, StickSlipUnderSlowDrag) {
  const StickSlip s = run_stick_slip(1e5, 30);
  // The spring winds up while the input sticks, breaks away near Fs, and the Stribeck drop
  // lets the input overshoot the drag speed before it sticks again.
  EXPECT_GE(s.slips, 3);
  EXPECT_GT(s.peak_speed, 0.15);
  EXPECT_GT(s.stuck_time, 0.2 * 30);
}

TEST(LuGre, RosenbrockDoesNotStallForStiffBristles) {
  // An explicit method needs steps in proportion to sigma0 (about 8e4, 8e5, 8e6 here); the
  // implicit one about 1.5e3 whatever sigma0.
  std::int64_t steps_soft = 0;
  for (double sigma0 : {1e5, 1e6, 1e7}) {
    const StickSlip s = run_stick_slip(sigma0, 30);
    if (steps_soft == 0) steps_soft = s.steps;
    EXPECT_GE(s.slips, 3) << sigma0;
    EXPECT_LT(s.steps, 5000) << sigma0;
    EXPECT_LT(s.steps, 2 * steps_soft) << sigma0;
  }
}

TEST(LuGre, PreslidingHysteresisBelowBreakaway) {
  // A torque of half the Coulomb level, alternating at 1 Hz: the input only deflects the
  // bristles (about A/sigma0), but the force-displacement curve is a loop.
  const double sigma0 = 1e5, amp = 0.5;
  GearParams p = testing::bare_gear(1, 1.0, 1.0, 1e-9);
  p.friction = LuGreFriction{sigma0, 2 * std::sqrt(sigma0), 0.4, 1.0, 1.5, 1e-3};
  p.input = TorqueInput{{0, amp, 1.0, 0}};
  const GearModel model(p);
  const StateLayout& L = model.layout();
  std::vector<double> y(L.size, 0.0);
  const testing::GearRun run =
      testing::run_gear(model, y, 5.0, 10000, 1e-8, 1e-8, solver::IntegratorKind::kRosenbrock);
  double max_angle = 0, area = 0;
  const std::size_t n = run.samples.size(), first = n - 1 - 10000;
  for (const auto& s : run.samples) max_angle = std::max(max_angle, std::abs(s.out.theta1));
  double lo = 1e9, hi = -1e9;
  for (std::size_t i = first; i + 1 < n; ++i) {
    const auto& a = run.samples[i].out;
    const auto& b = run.samples[i + 1].out;
    area += 0.5 * (a.friction_torque + b.friction_torque) * (b.theta1 - a.theta1);
    lo = std::min(lo, a.theta1);
    hi = std::max(hi, a.theta1);
  }
  EXPECT_LT(max_angle, 3 * amp / sigma0);  // no gross sliding
  EXPECT_GT(max_angle, 0.5 * amp / sigma0);
  EXPECT_GT(area, 0.05 * amp * (hi - lo));  // a loop, not a line
  const double lost =
      run.samples[n - 1].y[L.dissipated_energy] - run.samples[first].y[L.dissipated_energy];
  EXPECT_NEAR(lost / area, 1.0, 0.02);
}

}  // namespace
}  // namespace wavebench::model
