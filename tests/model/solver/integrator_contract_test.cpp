// The contract every integrator meets, checked against closed-form solutions.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "test_problems.hpp"
#include "wavebench/model/solver/integrators.hpp"
#include "wavebench/model/solver/trajectory_runner.hpp"

namespace wavebench::model::solver {
namespace {

using testing::ExponentialDecay;
using testing::LinearOscillator;
constexpr double kPi = std::numbers::pi;

struct IntegratorCase {
  std::string label;
  IntegratorKind kind;
  Tolerances tolerances;
  double fixed_step;
  double bound;  // absolute error expected on O(1) solutions at these settings
};

std::string case_name(const ::testing::TestParamInfo<IntegratorCase>& info) {
  return info.param.label;
}

class IntegratorContract : public ::testing::TestWithParam<IntegratorCase> {
 protected:
  std::unique_ptr<Integrator> make(double max_step = 0) const {
    const auto& p = GetParam();
    return make_integrator(p.kind, p.tolerances, p.fixed_step, max_step);
  }
  double bound() const { return GetParam().bound; }
};

// Steps to t_end and returns the final state.
std::vector<double> integrate(Integrator& integrator, const OdeSystem& system, double t0,
                              std::vector<double> y0, double t_end) {
  integrator.initialize(system, t0, y0, {}, 0);
  while (integrator.current_time() < t_end) integrator.step(t_end);
  auto s = integrator.current_state();
  return {s.begin(), s.end()};
}

TEST_P(IntegratorContract, ExponentialDecayMatchesClosedForm) {
  const ExponentialDecay system(2.0);
  auto integrator = make();
  const auto y = integrate(*integrator, system, 0.0, {1.0}, 3.0);
  EXPECT_DOUBLE_EQ(integrator->current_time(), 3.0);
  EXPECT_NEAR(y[0], system.exact(3.0, 1.0), bound() * 1e-2);
  EXPECT_GT(integrator->counters().steps, 0);
}

TEST_P(IntegratorContract, UndampedOscillatorMatchesClosedForm) {
  const double w0 = 2 * kPi;
  const LinearOscillator system(w0, 0.0);
  auto integrator = make();
  const auto y = integrate(*integrator, system, 0.0, {1.0, 0.0}, 5.25);
  double x = 0, v = 0;
  system.free_response(5.25, 1.0, 0.0, x, v);
  EXPECT_NEAR(y[0], x, bound());
  EXPECT_NEAR(y[1] / w0, v / w0, bound());
}

TEST_P(IntegratorContract, DampedOscillatorMatchesClosedForm) {
  const double w0 = 2 * kPi;
  const LinearOscillator system(w0, 0.1);
  auto integrator = make();
  for (double t_end : {0.3, 1.7, 4.0}) {
    const auto y = integrate(*integrator, system, 0.0, {0.5, 2.0}, t_end);
    double x = 0, v = 0;
    system.free_response(t_end, 0.5, 2.0, x, v);
    EXPECT_NEAR(y[0], x, bound()) << "t = " << t_end;
    EXPECT_NEAR(y[1] / w0, v / w0, bound()) << "t = " << t_end;
  }
}

TEST_P(IntegratorContract, ForcedOscillatorStaysOnSteadyState) {
  // Starting on the steady-state response, the exact solution is that response for all t; a
  // wrong stage time c_i (or a missing df/dt) shows up here and not in the autonomous cases.
  const double w0 = 2 * kPi * 3.0, w = 2 * kPi * 1.3;
  const LinearOscillator system(w0, 0.05, w0 * w0, w);
  double x0 = 0, v0 = 0;
  system.steady_state(0.0, x0, v0);
  auto integrator = make();
  const auto y = integrate(*integrator, system, 0.0, {x0, v0}, 2.0);
  double x = 0, v = 0;
  system.steady_state(2.0, x, v);
  EXPECT_NEAR(y[0], x, 4 * bound());
  EXPECT_NEAR(y[1] / w, v / w, 4 * bound());
}

TEST_P(IntegratorContract, DenseOutputIsAccurateBetweenSteps) {
  const double w0 = 2 * kPi;
  const LinearOscillator system(w0, 0.0);
  auto integrator = make();
  integrator->initialize(system, 0.0, std::vector<double>{1.0, 0.0}, {}, 0);
  double worst = 0;
  std::vector<double> y(2);
  double widest_step = 0;
  while (integrator->current_time() < 2.0) {
    integrator->step(2.0);
    const double a = integrator->previous_time(), b = integrator->current_time();
    widest_step = std::max(widest_step, b - a);
    for (int j = 1; j < 8; ++j) {
      const double t = a + (b - a) * j / 8.0;
      integrator->dense_output(t, y);
      worst = std::max(worst, std::fabs(y[0] - std::cos(w0 * t)));
    }
  }
  // Linear interpolation would be off by ~w0^2*h^2/8: far more than the bound at these steps.
  EXPECT_GT(w0 * w0 * widest_step * widest_step / 8, 10 * bound());
  EXPECT_LT(worst, bound());
}

TEST_P(IntegratorContract, DenseOutputReproducesStepEnds) {
  const ExponentialDecay system(1.0);
  auto integrator = make();
  integrator->initialize(system, 0.0, std::vector<double>{1.0}, {}, 0);
  std::vector<double> y(1);
  for (int i = 0; i < 5; ++i) {
    integrator->step(10.0);
    integrator->dense_output(integrator->current_time(), y);
    EXPECT_NEAR(y[0], integrator->current_state()[0], 1e-15);
    integrator->dense_output(integrator->previous_time(), y);
    EXPECT_NEAR(y[0], system.exact(integrator->previous_time(), 1.0), bound());
  }
}

TEST_P(IntegratorContract, LocatesOscillatorZeroCrossingAtHalfPi) {
  // x = cos t crosses zero downwards at t = pi/2.
  struct Crossing final : public OdeSystem {
    std::size_t continuous_size() const override { return 2; }
    void derivatives(double, std::span<const double> y, std::span<const double>,
                     std::span<double> f) const override {
      f[0] = y[1];
      f[1] = -y[0];
    }
    std::size_t witness_count() const override { return 1; }
    void witnesses(double, std::span<const double> y, std::span<const double>,
                   std::span<double> g) const override {
      g[0] = y[0];
    }
  } system;
  auto integrator = make();
  TrajectoryOptions options;
  options.t_end = 2.0;
  TrajectoryRunner runner(*integrator, system, options);
  std::vector<double> y{1.0, 0.0};
  const auto result = runner.run(0.0, y, {});
  ASSERT_EQ(result.events.size(), 1u);
  EXPECT_NEAR(result.events[0].t, kPi / 2, 1e-9);
  EXPECT_EQ(result.events[0].direction, -1);
  EXPECT_EQ(result.events[0].witness, 0u);
  EXPECT_NEAR(y[0], std::cos(2.0), 10 * bound());
}

TEST_P(IntegratorContract, SamplesLieExactlyOnTheGrid) {
  const double w0 = 2 * kPi * 5;
  const LinearOscillator system(w0, 0.02);
  auto integrator = make();
  TrajectoryOptions options;
  options.t_end = 1.0;
  options.sample_rate = 997.0;  // incommensurate with any step size
  options.sample_t0 = 0.1;
  TrajectoryRunner runner(*integrator, system, options);
  std::vector<double> times;
  double worst = 0;
  runner.on_sample([&](double t, std::span<const double> y, std::span<const double>) {
    times.push_back(t);
    double x = 0, v = 0;
    system.free_response(t, 1.0, 0.0, x, v);
    worst = std::max(worst, std::fabs(y[0] - x));
  });
  std::vector<double> y{1.0, 0.0};
  const auto result = runner.run(0.0, y, {});
  // Samples at 0.1 + k/997 for k = 0 .. floor(0.9*997) = 897.
  ASSERT_EQ(times.size(), 898u);
  EXPECT_EQ(result.samples, 898);
  for (std::size_t k = 0; k < times.size(); ++k) {
    ASSERT_EQ(times[k], 0.1 + static_cast<double>(k) / 997.0) << "k = " << k;
  }
  EXPECT_LT(worst, 2 * bound());
}

TEST_P(IntegratorContract, EnergyOfUndampedOscillatorDriftsLittleOver1000Periods) {
  const double w0 = 2 * kPi;
  const LinearOscillator system(w0, 0.0);
  const auto& p = GetParam();
  // Tight settings: rtol 1e-12 for the adaptive methods, 1/1000 period for Rk4 (whose energy
  // falls by (w h)^6/72 a step: 5e-10 over the run).
  auto integrator = make_integrator(p.kind, {1e-12, 1e-14}, 1.0 / 1000, 0);
  const auto y = integrate(*integrator, system, 0.0, {1.0, 0.0}, 1000.0);
  const double e0 = system.energy(std::vector<double>{1.0, 0.0});
  EXPECT_LT(std::fabs(system.energy(y) - e0) / e0, 1e-8);
}

TEST_P(IntegratorContract, ResetRestartsFromTheGivenState) {
  const ExponentialDecay system(1.5);
  auto integrator = make();
  integrator->initialize(system, 0.0, std::vector<double>{1.0}, {}, 0);
  while (integrator->current_time() < 1.0) integrator->step(1.0);
  // An event at t = 1 sets y = 3: from there y = 3 exp(-1.5 (t - 1)).
  integrator->reset(1.0, std::vector<double>{3.0});
  EXPECT_EQ(integrator->current_time(), 1.0);
  EXPECT_EQ(integrator->current_state()[0], 3.0);
  while (integrator->current_time() < 2.5) integrator->step(2.5);
  EXPECT_NEAR(integrator->current_state()[0], 3.0 * std::exp(-1.5 * 1.5), 3e-2 * bound());
}

TEST_P(IntegratorContract, StepsRespectMaxStepAndTMax) {
  const LinearOscillator system(2 * kPi, 0.1);
  const double max_step = GetParam().kind == IntegratorKind::kRk4 ? 1e-3 : 0.01;
  auto integrator = make(max_step);
  integrator->initialize(system, 0.0, std::vector<double>{1.0, 0.0}, {}, 0);
  double widest = 0;
  while (integrator->current_time() < 0.737) {
    const double t = integrator->step(0.737);
    EXPECT_LE(t, 0.737);
    widest = std::max(widest, t - integrator->previous_time());
  }
  EXPECT_EQ(integrator->current_time(), 0.737);
  EXPECT_LE(widest, max_step * (1 + 1e-9));
}

// Every integrator of the registry, at settings derived from what it is: a new integrator is
// covered by its one registry row. Adaptive methods at tolerances that put a method of order p
// near 1e-8 on these O(1) problems; fixed-step methods at 1 ms.
std::vector<IntegratorCase> registry_cases() {
  std::vector<IntegratorCase> cases;
  for (const auto& entry : integrator_registry()) {
    const bool high_order = make_integrator(entry.kind, {}, 1e-3, 0)->order() >= 5;
    const Tolerances tolerances = !entry.adaptive ? Tolerances{}
                                  : high_order    ? Tolerances{1e-10, 1e-12}
                                                  : Tolerances{1e-9, 1e-11};
    cases.push_back(
        {std::string(entry.name), entry.kind, tolerances, entry.adaptive ? 0.0 : 1e-3, 1e-7});
  }
  return cases;
}

INSTANTIATE_TEST_SUITE_P(AllIntegrators, IntegratorContract, ::testing::ValuesIn(registry_cases()),
                         case_name);

TEST(IntegratorRegistry, EachRowMakesTheIntegratorItNamesOnce) {
  std::vector<std::string> names;
  for (const auto& entry : integrator_registry()) {
    const auto integrator = make_integrator(entry.kind, {}, 1e-3, 0);
    EXPECT_EQ(integrator->name(), entry.name);
    EXPECT_EQ(std::count(names.begin(), names.end(), integrator->name()), 0) << entry.name;
    names.push_back(integrator->name());
  }
  EXPECT_EQ(names.size(), 3u);  // DormandPrince45, Rk4, Rosenbrock4
}

}  // namespace
}  // namespace wavebench::model::solver
