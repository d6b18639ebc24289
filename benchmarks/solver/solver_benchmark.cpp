// Integrator throughput: steps/s and RHS evaluations/s on a forced oscillator, and a
// gear-like run (4 states, a 24 kHz forcing line, 2 s, sampled at 100 kHz) through the
// TrajectoryRunner, the shape of the XB-80 reference case. Figures, not assertions.
#include <benchmark/benchmark.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "wavebench/model/solver/integrators.hpp"
#include "wavebench/model/solver/trajectory_runner.hpp"

namespace {

using namespace wavebench::model::solver;
constexpr double kTwoPi = 2 * std::numbers::pi;

// x'' + 2 zeta w0 x' + w0^2 x = F cos(w t): 2 states, one cos per evaluation.
class ForcedOscillator final : public OdeSystem {
 public:
  std::size_t continuous_size() const override { return 2; }
  void derivatives(double t, std::span<const double> y, std::span<const double>,
                   std::span<double> f) const override {
    f[0] = y[1];
    f[1] = -w0_ * w0_ * y[0] - 2 * zeta_ * w0_ * y[1] + w0_ * w0_ * std::cos(w_ * t);
  }

 private:
  double w0_ = kTwoPi * 100, zeta_ = 0.05, w_ = kTwoPi * 37;
};

// Two inertias in deviation coordinates with a proportional speed loop on the input:
// state (phi1, u1, q, dq): phi1 = theta1 - Omega t, u1 = omega1 - Omega, q = theta2 - theta1/N.
// Twist Delta = -q - e, e = A1 sin(2(1+1/N) theta1) + A2 sin(2 zC theta1): a ~90 Hz line and
// the 24 kHz tooth-mesh line at 2680 rpm.
class GearLike final : public OdeSystem {
 public:
  std::size_t continuous_size() const override { return 4; }
  void error_scale(std::span<double> s) const override {
    s[0] = 1e-3;
    s[1] = 1e-1;
    s[2] = 1e-5;
    s[3] = 1e-2;
  }
  void derivatives(double t, std::span<const double> y, std::span<const double>,
                   std::span<double> f) const override {
    const double theta1 = omega_ * t + y[0];
    const double omega1 = omega_ + y[1];
    const double a1 = 2 * (1 + 1 / n_), a2 = 2 * zc_;
    const double e = amp1_ * std::sin(a1 * theta1) + amp2_ * std::sin(a2 * theta1);
    const double de =
        omega1 * (amp1_ * a1 * std::cos(a1 * theta1) + amp2_ * a2 * std::cos(a2 * theta1));
    const double twist = -y[2] - e;
    const double twist_rate = -y[3] - de;
    const double tg = k_ * twist + c_ * twist_rate;
    const double omega2 = omega1 / n_ + y[3];
    const double tm = load_ / n_ - kp_ * y[1];
    const double du1 = (tm - tg / n_) / j1_;
    const double domega2 = (tg - cz_ * omega2 - load_) / j2_;
    f[0] = y[1];
    f[1] = du1;
    f[2] = y[3];
    f[3] = domega2 - du1 / n_;
  }

 private:
  double n_ = 134, zc_ = 270, omega_ = 2680 * kTwoPi / 60, j1_ = 2.2e-4, j2_ = 0.2839;
  double k_ = 1.0e5, c_ = 2 * 0.06 * std::sqrt(0.265 * 1.0e5), cz_ = 0.05, load_ = 5.0;
  double kp_ = 0.5, amp1_ = 20.0 / 206265, amp2_ = 0.3 / 206265;
};

std::unique_ptr<Integrator> make(int which) {
  switch (which) {
    case 0:
      return make_integrator(IntegratorKind::kDormandPrince45, {1e-6, 1e-9}, 0, 0);
    case 1:
      return make_integrator(IntegratorKind::kRk4, {}, 1e-4, 0);
    default:
      return make_integrator(IntegratorKind::kRosenbrock, {1e-6, 1e-9}, 0, 0);
  }
}

void BM_ForcedOscillatorSteps(benchmark::State& state) {
  const ForcedOscillator system;
  auto integrator = make(static_cast<int>(state.range(0)));
  std::int64_t steps = 0, rhs = 0;
  for (auto _ : state) {
    integrator->initialize(system, 0.0, std::vector<double>{0.0, 0.0}, {}, 0);
    while (integrator->current_time() < 1.0) integrator->step(1.0);
    steps += integrator->counters().steps;
    rhs += integrator->counters().rhs_evaluations;
  }
  state.SetLabel(integrator->name());
  state.counters["steps/s"] =
      benchmark::Counter(static_cast<double>(steps), benchmark::Counter::kIsRate);
  state.counters["rhs/s"] =
      benchmark::Counter(static_cast<double>(rhs), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_ForcedOscillatorSteps)->Arg(0)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond);

// 2 s of the gear-like system sampled at 100 kHz: the XB-80 budget is 0.2 s wall.
void BM_GearLike2sAt100kHz(benchmark::State& state) {
  const GearLike system;
  auto integrator = make(static_cast<int>(state.range(0)));
  std::int64_t steps = 0, samples = 0;
  double checksum = 0;
  for (auto _ : state) {
    TrajectoryOptions options;
    options.t_end = 2.0;
    options.sample_rate = 100e3;
    TrajectoryRunner runner(*integrator, system, options);
    runner.on_sample(
        [&](double, std::span<const double> y, std::span<const double>) { checksum += y[2]; });
    std::vector<double> y(4, 0.0);
    const auto result = runner.run(0.0, y, {});
    steps += result.counters.steps;
    samples += result.samples;
  }
  benchmark::DoNotOptimize(checksum);
  state.SetLabel(integrator->name());
  state.counters["steps/run"] =
      benchmark::Counter(static_cast<double>(steps), benchmark::Counter::kAvgIterations);
  state.counters["samples/run"] =
      benchmark::Counter(static_cast<double>(samples), benchmark::Counter::kAvgIterations);
}
BENCHMARK(BM_GearLike2sAt100kHz)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
