// Event location, restarts, fixed-rate sampling and the guards of TrajectoryRunner.
#include "wavebench/model/solver/trajectory_runner.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "test_problems.hpp"
#include "wavebench/model/solver/dormand_prince45.hpp"
#include "wavebench/model/solver/integrators.hpp"
#include "wavebench/model/solver/rk4.hpp"

namespace wavebench::model::solver {
namespace {

constexpr double kGravity = 9.81;

// A ball dropped from height h0 bouncing with restitution e; d[0] counts bounces.
class BouncingBall final : public OdeSystem {
 public:
  explicit BouncingBall(double restitution) : e_(restitution) {}
  std::size_t continuous_size() const override { return 2; }
  std::size_t discrete_size() const override { return 1; }
  void derivatives(double, std::span<const double> y, std::span<const double>,
                   std::span<double> f) const override {
    f[0] = y[1];
    f[1] = -kGravity;
  }
  std::size_t witness_count() const override { return 1; }
  void witnesses(double, std::span<const double> y, std::span<const double>,
                 std::span<double> g) const override {
    g[0] = y[0];
  }
  void on_event(std::size_t, double, std::span<double> y, std::span<double> d) const override {
    y[0] = 0;  // on the floor exactly, so the witness restarts from zero, not from below
    y[1] = -e_ * y[1];
    d[0] += 1;
  }
  // Closed form: first impact at sqrt(2 h0/g), then flights of 2 e^k v1 / g.
  std::vector<double> bounce_times(double h0, int count) const {
    std::vector<double> times;
    double t = std::sqrt(2 * h0 / kGravity);
    double v = kGravity * t;
    for (int k = 0; k < count; ++k) {
      times.push_back(t);
      v *= e_;
      t += 2 * v / kGravity;
    }
    return times;
  }

 private:
  double e_;
};

TEST(TrajectoryRunner, BouncingBallImpactsMatchClosedForm) {
  const BouncingBall system(0.8);
  for (auto kind :
       {IntegratorKind::kDormandPrince45, IntegratorKind::kRk4, IntegratorKind::kRosenbrock}) {
    auto integrator = make_integrator(kind, {1e-10, 1e-12}, 1e-2, 0);
    // Before the Zeno point (4.06 s): 12 bounces, the last flights a few hundredths long.
    TrajectoryOptions options;
    options.t_end = 3.9;
    TrajectoryRunner runner(*integrator, system, options);
    std::vector<double> y{1.0, 0.0}, d{0.0};
    const auto result = runner.run(0.0, y, d);
    const auto expected = system.bounce_times(1.0, 40);
    std::size_t in_range = 0;
    while (in_range < expected.size() && expected[in_range] <= options.t_end) ++in_range;
    EXPECT_GE(in_range, 10u);
    ASSERT_EQ(result.events.size(), in_range) << integrator->name();
    for (std::size_t k = 0; k < in_range; ++k) {
      EXPECT_NEAR(result.events[k].t, expected[k], 1e-9) << integrator->name() << " k=" << k;
      EXPECT_EQ(result.events[k].direction, -1);
    }
    EXPECT_EQ(d[0], static_cast<double>(in_range));
    EXPECT_EQ(result.suppressed_events, 0);
  }
}

// y' = 1 from 0 (so y = t); witness k is y - root[k]. One Rk4 step covers all of them.
class Ramp final : public OdeSystem {
 public:
  explicit Ramp(std::vector<double> roots) : roots_(std::move(roots)) {}
  std::size_t continuous_size() const override { return 1; }
  std::size_t discrete_size() const override { return 1; }
  void derivatives(double, std::span<const double>, std::span<const double>,
                   std::span<double> f) const override {
    f[0] = 1;
  }
  std::size_t witness_count() const override { return roots_.size(); }
  void witnesses(double, std::span<const double> y, std::span<const double>,
                 std::span<double> g) const override {
    for (std::size_t k = 0; k < roots_.size(); ++k) g[k] = y[0] - roots_[k];
  }
  void on_event(std::size_t, double, std::span<double> y, std::span<double> d) const override {
    d[0] += 1;
    y[0] -= kick_;
  }
  double kick_ = 0;

 private:
  std::vector<double> roots_;
};

TEST(TrajectoryRunner, SeveralWitnessesInOneStepFireInTimeOrder) {
  const Ramp system({0.3, 0.2, 0.25});
  Rk4 integrator(1.0);
  TrajectoryOptions options;
  options.t_end = 1.0;
  TrajectoryRunner runner(integrator, system, options);
  std::vector<double> y{0.0}, d{0.0};
  const auto result = runner.run(0.0, y, d);
  ASSERT_EQ(result.events.size(), 3u);
  EXPECT_EQ(result.events[0].witness, 1u);
  EXPECT_EQ(result.events[1].witness, 2u);
  EXPECT_EQ(result.events[2].witness, 0u);
  EXPECT_NEAR(result.events[0].t, 0.2, 1e-12);
  EXPECT_NEAR(result.events[1].t, 0.25, 1e-12);
  EXPECT_NEAR(result.events[2].t, 0.3, 1e-12);
  for (const auto& e : result.events) EXPECT_EQ(e.direction, +1);
  // Each event restarts the integrator: 3 truncated steps and then the rest of the interval.
  EXPECT_EQ(result.counters.steps, 4);
  EXPECT_DOUBLE_EQ(y[0], 1.0);
}

TEST(TrajectoryRunner, SimultaneousRootsFireTogether) {
  const Ramp system({0.5, 0.5});
  DormandPrince45 integrator(StepControl{});
  TrajectoryOptions options;
  options.t_end = 1.0;
  TrajectoryRunner runner(integrator, system, options);
  std::vector<double> y{0.0}, d{0.0};
  const auto result = runner.run(0.0, y, d);
  ASSERT_EQ(result.events.size(), 2u);
  EXPECT_EQ(result.events[0].t, result.events[1].t);
  EXPECT_EQ(result.events[0].witness, 0u);
  EXPECT_EQ(result.events[1].witness, 1u);
  EXPECT_EQ(d[0], 2.0);
}

TEST(TrajectoryRunner, ZenoGuardSuppressesImmediateRedetection) {
  // on_event knocks the state back across the root by 1e-11 (more than the root's 1e-12
  // bracket): without the guard the witness would cross again ~1e-11 s later, forever.
  Ramp system({0.5});
  system.kick_ = 1e-11;
  DormandPrince45 integrator(StepControl{});
  TrajectoryOptions options;
  options.t_end = 1.0;
  options.min_event_separation = 1e-9;
  TrajectoryRunner runner(integrator, system, options);
  std::vector<double> y{0.0}, d{0.0};
  const auto result = runner.run(0.0, y, d);
  EXPECT_EQ(result.events.size(), 1u);
  EXPECT_EQ(result.suppressed_events, 1);
  EXPECT_NEAR(y[0], 1.0 - 1e-11, 1e-14);
}

TEST(TrajectoryRunner, SamplesContinueExactlyOnTheGridThroughEvents) {
  const BouncingBall system(0.9);
  auto integrator = make_integrator(IntegratorKind::kDormandPrince45, {1e-10, 1e-12}, 0, 0);
  TrajectoryOptions options;
  options.t_end = 3.0;
  options.sample_rate = 1000;
  TrajectoryRunner runner(*integrator, system, options);
  std::vector<double> times;
  double worst = 0;
  const auto impacts = system.bounce_times(1.0, 10);
  runner.on_sample([&](double t, std::span<const double> y, std::span<const double> d) {
    times.push_back(t);
    // Closed-form height: free flight since the last impact.
    const auto bounces = static_cast<std::size_t>(d[0]);
    double h = 0;
    if (bounces == 0) {
      h = 1.0 - 0.5 * kGravity * t * t;
    } else {
      const double t_hit = impacts[bounces - 1];
      const double v_up = kGravity * impacts[0] * std::pow(0.9, static_cast<double>(bounces));
      const double s = t - t_hit;
      h = v_up * s - 0.5 * kGravity * s * s;
    }
    worst = std::max(worst, std::fabs(y[0] - h));
  });
  std::vector<double> y{1.0, 0.0}, d{0.0};
  const auto result = runner.run(0.0, y, d);
  ASSERT_EQ(times.size(), 3001u);
  for (std::size_t k = 0; k < times.size(); ++k) {
    ASSERT_EQ(times[k], static_cast<double>(k) / 1000.0) << k;
  }
  EXPECT_EQ(result.samples, 3001);
  EXPECT_EQ(result.events.size(), 4u);  // 0.45, 1.26, 1.99, 2.65 s
  EXPECT_LT(worst, 1e-8);
}

TEST(TrajectoryRunner, SamplingStartsAtSampleT0AndCoversShortSteps) {
  const testing::ExponentialDecay system(1.0);
  Rk4 integrator(0.25);  // 4 steps a second against 100 samples a second
  TrajectoryOptions options;
  options.t_end = 2.0;
  options.sample_rate = 100;
  options.sample_t0 = 0.5;
  TrajectoryRunner runner(integrator, system, options);
  std::vector<double> times;
  runner.on_sample(
      [&](double t, std::span<const double>, std::span<const double>) { times.push_back(t); });
  std::vector<double> y{1.0};
  const auto result = runner.run(0.0, y, {});
  ASSERT_EQ(times.size(), 151u);
  EXPECT_EQ(times.front(), 0.5);
  EXPECT_EQ(times.back(), 0.5 + 150 / 100.0);
  EXPECT_EQ(result.counters.steps, 8);
}

TEST(TrajectoryRunner, MaxStepsThrowsInsteadOfHanging) {
  // Explicit method on a stiff problem: the stability bound forces ~1e6 steps.
  const testing::ProtheroRobinson system(1e6);
  auto integrator = make_integrator(IntegratorKind::kDormandPrince45, {1e-6, 1e-8}, 0, 0);
  TrajectoryOptions options;
  options.t_end = 10.0;
  options.max_steps = 1000;
  TrajectoryRunner runner(*integrator, system, options);
  std::vector<double> y{2.0};
  try {
    runner.run(0.0, y, {});
    FAIL() << "expected std::runtime_error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("max_steps = 1000"), std::string::npos) << e.what();
  }
  EXPECT_EQ(integrator->counters().steps, 1000);
}

TEST(TrajectoryRunner, ProgressRisesToOne) {
  const testing::ExponentialDecay system(1.0);
  Rk4 integrator(1e-3);
  TrajectoryOptions options;
  options.t_end = 1.0;
  options.progress_interval = 0.1;
  TrajectoryRunner runner(integrator, system, options);
  std::vector<double> fractions;
  runner.on_progress([&](double f) { fractions.push_back(f); });
  std::vector<double> y{1.0};
  runner.run(0.0, y, {});
  ASSERT_GE(fractions.size(), 10u);
  ASSERT_LE(fractions.size(), 11u);
  for (std::size_t i = 1; i < fractions.size(); ++i) EXPECT_GT(fractions[i], fractions[i - 1]);
  EXPECT_EQ(fractions.back(), 1.0);
}

TEST(TrajectoryRunner, RejectsBadOptionsByName) {
  const testing::ExponentialDecay system(1.0);
  Rk4 integrator(1e-3);
  TrajectoryOptions options;
  options.sample_rate = -5;
  try {
    TrajectoryRunner runner(integrator, system, options);
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("sample_rate"), std::string::npos) << e.what();
  }
  EXPECT_THROW(make_integrator(IntegratorKind::kRk4, {}, 0.0, 0), std::invalid_argument);
  EXPECT_THROW(make_integrator(IntegratorKind::kDormandPrince45, {-1e-6, 1e-9}, 0, 0),
               std::invalid_argument);
}

TEST(TrajectoryRunner, RejectsAZeroErrorScaleByIndex) {
  struct ZeroScale final : public OdeSystem {
    std::size_t continuous_size() const override { return 2; }
    void derivatives(double, std::span<const double>, std::span<const double>,
                     std::span<double> f) const override {
      f[0] = f[1] = 0;
    }
    void error_scale(std::span<double> s) const override {
      s[0] = 1;
      s[1] = 0;
    }
  } system;
  for (auto kind : {IntegratorKind::kDormandPrince45, IntegratorKind::kRosenbrock}) {
    auto integrator = make_integrator(kind, {}, 0, 0);
    try {
      integrator->initialize(system, 0.0, std::vector<double>{0.0, 0.0}, {}, 0);
      FAIL() << "expected std::invalid_argument";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("error_scale()[1]"), std::string::npos) << e.what();
    }
  }
}

TEST(TrajectoryRunner, CountsEvaluationsExactly) {
  // DormandPrince45: 1 at start, 1 in the first-step guess, 6 per attempted step (FSAL).
  const testing::ExponentialDecay system(1.0);
  auto dp = make_integrator(IntegratorKind::kDormandPrince45, {1e-8, 1e-10}, 0, 0);
  TrajectoryOptions options;
  options.t_end = 3.0;
  TrajectoryRunner dp_runner(*dp, system, options);
  std::vector<double> y{1.0};
  auto r = dp_runner.run(0.0, y, {});
  EXPECT_EQ(r.counters.rhs_evaluations, 2 + 6 * (r.counters.steps + r.counters.rejected_steps));
  // Rk4: 1 at start and 4 per step.
  Rk4 rk(0.01);
  TrajectoryRunner rk_runner(rk, system, options);
  y = {1.0};
  r = rk_runner.run(0.0, y, {});
  EXPECT_EQ(r.counters.steps, 300);
  EXPECT_EQ(r.counters.rhs_evaluations, 1 + 4 * 300);
  // Rosenbrock4 with a finite-difference Jacobian (n = 1): per accepted step 1 Jacobian =
  // n + 2 evaluations (columns, central df/dt) and 1 at the new point; 5 per attempt.
  auto ros = make_integrator(IntegratorKind::kRosenbrock, {1e-8, 1e-10}, 0, 0);
  TrajectoryRunner ros_runner(*ros, system, options);
  y = {1.0};
  r = ros_runner.run(0.0, y, {});
  EXPECT_EQ(r.counters.jacobian_evaluations, r.counters.steps);
  EXPECT_EQ(r.counters.rhs_evaluations,
            2 + 5 * (r.counters.steps + r.counters.rejected_steps) + r.counters.steps * (1 + 3));
}

}  // namespace
}  // namespace wavebench::model::solver
