// Measured convergence orders: the global error at fixed steps h, h/2, h/4, ... falls with the
// method's order. Catches a wrong tableau entry, which closed-form spot checks at tight
// tolerances can miss.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include "test_problems.hpp"
#include "wavebench/model/solver/dormand_prince45.hpp"
#include "wavebench/model/solver/rk4.hpp"
#include "wavebench/model/solver/rosenbrock4.hpp"

namespace wavebench::model::solver {
namespace {

using testing::ExpSine;
using testing::LinearOscillator;
using testing::NonlinearRotation;

// Least-squares slope of log(error) against log(h).
double fitted_order(const std::vector<double>& h, const std::vector<double>& err) {
  const auto n = static_cast<double>(h.size());
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (std::size_t i = 0; i < h.size(); ++i) {
    const double x = std::log(h[i]), y = std::log(err[i]);
    sx += x;
    sy += y;
    sxx += x * x;
    sxy += x * y;
  }
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

std::unique_ptr<Integrator> fixed_step_integrator(const std::string& method, double h) {
  StepControl control;
  control.fixed_step = h;
  if (method == "Rk4") return std::make_unique<Rk4>(h);
  if (method == "DormandPrince45") return std::make_unique<DormandPrince45>(control);
  return std::make_unique<Rosenbrock4>(control);
}

// Global error at t_end of the nonlinear rotation from radius 1.2.
double global_error(Integrator& integrator, double t_end) {
  const NonlinearRotation system;
  integrator.initialize(system, 0.0, std::vector<double>{1.2, 0.0}, {}, 0);
  while (integrator.current_time() < t_end) integrator.step(t_end);
  return std::fabs(integrator.current_state()[0] - NonlinearRotation::exact_first(t_end, 1.2));
}

struct OrderCase {
  const char* method;
  double h0;
  double min_order;
  double max_order;
};

class ConvergenceOrder : public ::testing::TestWithParam<OrderCase> {};

TEST_P(ConvergenceOrder, GlobalErrorFallsAtTheMethodsOrder) {
  const auto& c = GetParam();
  std::vector<double> hs, errs;
  for (int k = 0; k < 4; ++k) {
    const double h = c.h0 / std::pow(2.0, k);
    auto integrator = fixed_step_integrator(c.method, h);
    hs.push_back(h);
    errs.push_back(global_error(*integrator, 4.0));
    EXPECT_EQ(integrator->counters().steps, std::lround(4.0 / h));
    EXPECT_EQ(integrator->counters().rejected_steps, 0);
  }
  const double p = fitted_order(hs, errs);
  EXPECT_GE(p, c.min_order) << c.method;
  EXPECT_LE(p, c.max_order) << c.method;
}

INSTANTIATE_TEST_SUITE_P(FixedSteps, ConvergenceOrder,
                         // Rosenbrock4's 4th-order error term is small on this problem: over these
                         // steps the error falls faster than h^4, so only its lower bound is tight.
                         ::testing::Values(OrderCase{"Rk4", 0.1, 3.7, 4.3},
                                           OrderCase{"DormandPrince45", 0.1, 4.7, 5.3},
                                           OrderCase{"Rosenbrock4", 0.1, 3.7, 6.0}),
                         [](const auto& param_info) {
                           return std::string(param_info.param.method);
                         });

TEST(ConvergenceOrder, RosenbrockKeepsItsOrderOnATimeDependentForcedOscillator) {
  // Explicit time dependence exercises the df/dt terms (finite differences here, no analytic
  // Jacobian): a wrong gamma_i coefficient leaves the autonomous order intact but not this one.
  const double w0 = 2 * std::numbers::pi, w = 2 * std::numbers::pi * 0.7;
  const LinearOscillator system(w0, 0.1, 5.0, w);
  double x0 = 0, v0 = 0, x1 = 0, v1 = 0;
  system.steady_state(0.0, x0, v0);
  system.steady_state(3.0, x1, v1);
  std::vector<double> hs, errs;
  for (int k = 0; k < 4; ++k) {
    const double h = 0.05 / std::pow(2.0, k);
    StepControl control;
    control.fixed_step = h;
    Rosenbrock4 integrator(control);
    integrator.initialize(system, 0.0, std::vector<double>{x0, v0}, {}, 0);
    while (integrator.current_time() < 3.0) integrator.step(3.0);
    hs.push_back(h);
    errs.push_back(std::fabs(integrator.current_state()[0] - x1));
  }
  const double p = fitted_order(hs, errs);
  EXPECT_GE(p, 3.7);
  EXPECT_LE(p, 4.5);
}

TEST(ConvergenceOrder, DormandPrinceDenseOutputIsFourthOrderInterpolation) {
  // Max error at step midpoints: the continuous extension's local error is O(h^5), so the
  // midpoint error falls like the global error, at order >= 4.5 here (linear interpolation
  // would give 2, Hermite 4).
  std::vector<double> hs, errs;
  for (int k = 0; k < 4; ++k) {
    const double h = 0.2 / std::pow(2.0, k);
    StepControl control;
    control.fixed_step = h;
    DormandPrince45 integrator(control);
    const ExpSine system;
    integrator.initialize(system, 0.0, std::vector<double>{1.0}, {}, 0);
    double worst = 0;
    std::vector<double> y(1);
    while (integrator.current_time() < 4.0) {
      integrator.step(4.0);
      for (double frac : {0.3, 0.5, 0.7}) {
        const double t = integrator.previous_time() +
                         frac * (integrator.current_time() - integrator.previous_time());
        integrator.dense_output(t, y);
        worst = std::max(worst, std::fabs(y[0] - ExpSine::exact(t)));
      }
    }
    hs.push_back(h);
    errs.push_back(worst);
  }
  EXPECT_GE(fitted_order(hs, errs), 4.5);
}

TEST(ConvergenceOrder, AdaptiveErrorFollowsTheTolerance) {
  // Tolerance proportionality: the global error of the adaptive methods tracks rtol within
  // two decades over six decades of rtol.
  for (int method = 0; method < 2; ++method) {
    for (double rtol : {1e-4, 1e-6, 1e-8, 1e-10}) {
      StepControl control;
      control.tolerances = {rtol, rtol};
      std::unique_ptr<Integrator> integrator;
      if (method == 0) {
        integrator = std::make_unique<DormandPrince45>(control);
      } else {
        integrator = std::make_unique<Rosenbrock4>(control);
      }
      const double err = global_error(*integrator, 4.0);
      EXPECT_LT(err, 100 * rtol) << integrator->name() << " rtol " << rtol;
      EXPECT_GT(err, 1e-4 * rtol) << integrator->name() << " rtol " << rtol;
    }
  }
}

}  // namespace
}  // namespace wavebench::model::solver
