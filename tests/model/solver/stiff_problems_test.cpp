// The implicit method on stiff problems: stiffness ratios of 1e6 and LuGre bristles with
// sigma0 up to 1e7, at step counts set by the slow dynamics, not by the stiff eigenvalue.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <vector>

#include "test_problems.hpp"
#include "wavebench/model/solver/integrators.hpp"
#include "wavebench/model/solver/rosenbrock4.hpp"
#include "wavebench/model/solver/trajectory_runner.hpp"

namespace wavebench::model::solver {
namespace {

using testing::ProtheroRobinson;

TEST(StiffProblems, RosenbrockFollowsProtheroRobinsonAtStiffness1e6) {
  const ProtheroRobinson system(1e6);
  auto integrator = make_integrator(IntegratorKind::kRosenbrock, {1e-6, 1e-8}, 0, 0);
  integrator->initialize(system, 0.0, std::vector<double>{2.0}, {}, 0);
  for (double t_check : {1e-7, 1e-5, 0.1, 1.0, 10.0}) {
    while (integrator->current_time() < t_check) integrator->step(t_check);
    EXPECT_NEAR(integrator->current_state()[0], system.exact(t_check, 2.0), 1e-6)
        << "t = " << t_check;
  }
  // An explicit method would need ~3e6 steps (stability bound h < 3.3e-6).
  EXPECT_LT(integrator->counters().steps, 300);
  EXPECT_EQ(integrator->counters().jacobian_evaluations, integrator->counters().steps);
}

TEST(StiffProblems, RosenbrockSamplesProtheroRobinsonFromDenseOutput) {
  // The 3rd-order interpolant's error grows like h^4 over a step, so sampled stiff runs cap
  // the step at a few sample periods.
  const ProtheroRobinson system(1e6);
  auto integrator = make_integrator(IntegratorKind::kRosenbrock, {1e-6, 1e-8}, 0, 0.05);
  TrajectoryOptions options;
  options.t_end = 10.0;
  options.sample_rate = 100;
  TrajectoryRunner runner(*integrator, system, options);
  double worst = 0;
  runner.on_sample([&](double t, std::span<const double> y, std::span<const double>) {
    worst = std::max(worst, std::fabs(y[0] - system.exact(t, 2.0)));
  });
  std::vector<double> y{2.0};
  const auto result = runner.run(0.0, y, {});
  EXPECT_EQ(result.samples, 1001);
  EXPECT_LT(worst, 1e-5);
  EXPECT_LT(result.counters.steps, 500);
}

// y' = A (y - p(t)) + p'(t) with A = V diag(-1, -1e6) V^-1 and p(t) = (sin t, cos 2t):
// y = p(t) + V diag(e^-t, e^-1e6 t) V^-1 (y0 - p(0)). Coupled, stiffness ratio 1e6.
class StiffCoupled final : public OdeSystem {
 public:
  StiffCoupled() {
    v_ << 1, 1, 1, -2;
    a_ = v_ * Eigen::Vector2d(-1, -1e6).asDiagonal() * v_.inverse();
  }
  std::size_t continuous_size() const override { return 2; }
  void derivatives(double t, std::span<const double> y, std::span<const double>,
                   std::span<double> f) const override {
    const Eigen::Vector2d dev(y[0] - std::sin(t), y[1] - std::cos(2 * t));
    const Eigen::Vector2d r = a_ * dev;
    f[0] = r[0] + std::cos(t);
    f[1] = r[1] - 2 * std::sin(2 * t);
  }
  Eigen::Vector2d exact(double t, const Eigen::Vector2d& y0) const {
    const Eigen::Vector2d c = v_.inverse() * (y0 - Eigen::Vector2d(0, 1));
    return Eigen::Vector2d(std::sin(t), std::cos(2 * t)) +
           v_ * Eigen::Vector2d(std::exp(-t) * c[0], std::exp(-1e6 * t) * c[1]);
  }

 private:
  Eigen::Matrix2d v_, a_;
};

TEST(StiffProblems, RosenbrockSolvesACoupledSystemWithStiffnessRatio1e6) {
  const StiffCoupled system;
  const Eigen::Vector2d y0(1.0, 3.0);
  auto integrator = make_integrator(IntegratorKind::kRosenbrock, {1e-7, 1e-9}, 0, 0);
  integrator->initialize(system, 0.0, std::vector<double>{y0[0], y0[1]}, {}, 0);
  for (double t_check : {1e-6, 1e-3, 0.5, 2.0, 5.0}) {
    while (integrator->current_time() < t_check) integrator->step(t_check);
    const Eigen::Vector2d exact = system.exact(t_check, y0);
    EXPECT_NEAR(integrator->current_state()[0], exact[0], 1e-5) << "t = " << t_check;
    EXPECT_NEAR(integrator->current_state()[1], exact[1], 1e-5) << "t = " << t_check;
  }
  EXPECT_LT(integrator->counters().steps, 1000);
}

// Robertson's chemical kinetics (Hairer & Wanner II, §IV.1): rate constants 0.04, 1e4, 3e7.
class Robertson final : public OdeSystem {
 public:
  std::size_t continuous_size() const override { return 3; }
  void error_scale(std::span<double> scale) const override {
    scale[0] = 1;
    scale[1] = 1e-5;  // y2 peaks at 3.6e-5
    scale[2] = 1;
  }
  void derivatives(double, std::span<const double> y, std::span<const double>,
                   std::span<double> f) const override {
    f[0] = -0.04 * y[0] + 1e4 * y[1] * y[2];
    f[1] = 0.04 * y[0] - 1e4 * y[1] * y[2] - 3e7 * y[1] * y[1];
    f[2] = 3e7 * y[1] * y[1];
  }
};

TEST(StiffProblems, RosenbrockMatchesRadauOnRobertson) {
  // Reference at t = 40: scipy's Radau IIA at rtol 1e-12 (an independent implicit method),
  // agreeing with the literature values of Hairer & Wanner's test set to 1e-13.
  const double reference[3] = {0.7158270687194069, 9.185534764557785e-06, 0.2841637457458306};
  const Robertson system;
  auto integrator = make_integrator(IntegratorKind::kRosenbrock, {1e-8, 1e-10}, 0, 0);
  integrator->initialize(system, 0.0, std::vector<double>{1.0, 0.0, 0.0}, {}, 0);
  while (integrator->current_time() < 40.0) integrator->step(40.0);
  const auto y = integrator->current_state();
  EXPECT_NEAR(y[0], reference[0], 1e-7);
  EXPECT_NEAR(y[1] / reference[1], 1.0, 1e-5);
  EXPECT_NEAR(y[2], reference[2], 1e-7);
  EXPECT_NEAR(y[0] + y[1] + y[2], 1.0, 1e-12);  // the method keeps linear invariants
  EXPECT_LT(integrator->counters().steps, 2000);
}

// A block on a moving belt, held by a spring, with LuGre friction (model.md §6):
//   x' = v, m v' = -k x - F_f, z' = w - |w| z / g(w), g = (Fc + (Fs - Fc) e^{-(w/vs)^2}) / s0,
//   F_f = s0 z + s1 z' + s2 w, w = v - v_belt (relative sliding speed).
// State (x, v, z). Stiff through s0; shows stick-slip: while stuck the block moves with the belt.
class LuGreBlock final : public OdeSystem {
 public:
  explicit LuGreBlock(double sigma0) : s0_(sigma0), s1_(2 * std::sqrt(sigma0 * m_)) {}
  std::size_t continuous_size() const override { return 3; }
  void error_scale(std::span<double> scale) const override {
    scale[0] = 1e-3;
    scale[1] = 1e-3;
    scale[2] = fs_ / s0_;  // bristle deflection: microns at sigma0 = 1e6
  }
  void derivatives(double, std::span<const double> y, std::span<const double>,
                   std::span<double> f) const override {
    const double w = y[1] - v_belt_;
    const double g = (fc_ + (fs_ - fc_) * std::exp(-(w / vs_) * (w / vs_))) / s0_;
    const double zdot = w - std::fabs(w) * y[2] / g;
    const double friction = s0_ * y[2] + s1_ * zdot + s2_ * w;
    f[0] = y[1];
    f[1] = (-k_ * y[0] - friction) / m_;
    f[2] = zdot;
  }
  double stick_force() const { return fs_; }
  double spring_rate() const { return k_; }

 private:
  double m_ = 1.0, k_ = 2.0, fc_ = 1.0, fs_ = 1.5, vs_ = 1e-3, s2_ = 0.4, v_belt_ = 0.1;
  double s0_, s1_;
};

class LuGreStiffness : public ::testing::TestWithParam<double> {};

TEST_P(LuGreStiffness, RosenbrockRunsStickSlipWithoutStalling) {
  const LuGreBlock system(GetParam());
  // max_step: an L-stable method damps the growing mode at break-away when its step is long,
  // so with no cap a loose tolerance can hold the block stuck well past the static limit.
  auto integrator = make_integrator(IntegratorKind::kRosenbrock, {1e-6, 1e-6}, 0, 1e-2);
  TrajectoryOptions options;
  options.t_end = 20.0;
  options.sample_rate = 1000;
  options.max_steps = 200'000;
  TrajectoryRunner runner(*integrator, system, options);
  double max_spring_force = 0;
  int stuck_samples = 0;
  runner.on_sample([&](double, std::span<const double> y, std::span<const double>) {
    max_spring_force = std::max(max_spring_force, system.spring_rate() * y[0]);
    if (std::fabs(y[1] - 0.1) < 1e-4) ++stuck_samples;
  });
  std::vector<double> y{0.0, 0.1, 0.0};
  const auto result = runner.run(0.0, y, {});
  // Stick-slip: the block rides with the belt until the spring force reaches about the
  // static friction level, then slips back.
  EXPECT_GT(stuck_samples, 5000);
  EXPECT_GT(max_spring_force, 0.97 * system.stick_force());
  EXPECT_LT(max_spring_force, 1.05 * system.stick_force());
  EXPECT_LT(result.counters.steps, 100'000) << "sigma0 = " << GetParam();
}

INSTANTIATE_TEST_SUITE_P(Sigma0, LuGreStiffness, ::testing::Values(1e5, 1e6, 1e7));

}  // namespace
}  // namespace wavebench::model::solver
