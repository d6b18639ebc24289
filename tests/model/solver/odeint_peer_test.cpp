// Independent peers: Boost.Odeint's runge_kutta_dopri5 and runge_kutta4 take the same fixed
// steps on the same problem; the states must agree to rounding. Odeint interpolates DOPRI5
// with Shampine's other 4th-order extension, which meets Hairer's (ours) at the step
// midpoint exactly and elsewhere within their O(h^5) difference.
// (Odeint's rosenbrock4 is no peer: its d4 has the wrong sign, see rosenbrock4.cpp.)
#include <gtest/gtest.h>

#include <boost/numeric/odeint/stepper/runge_kutta4.hpp>
#include <boost/numeric/odeint/stepper/runge_kutta_dopri5.hpp>
#include <cmath>
#include <vector>

#include "test_problems.hpp"
#include "wavebench/model/solver/dormand_prince45.hpp"
#include "wavebench/model/solver/rk4.hpp"

namespace wavebench::model::solver {
namespace {

using State = std::vector<double>;

// A nonlinear, time-dependent 2-state system for both sides.
class Duffing final : public OdeSystem {
 public:
  std::size_t continuous_size() const override { return 2; }
  void derivatives(double t, std::span<const double> y, std::span<const double>,
                   std::span<double> f) const override {
    f[0] = y[1];
    f[1] = -0.3 * y[1] - y[0] - 0.5 * y[0] * y[0] * y[0] + 2.0 * std::cos(1.4 * t);
  }
  void operator()(const State& y, State& f, double t) const { derivatives(t, y, {}, f); }
};

TEST(OdeintPeer, DormandPrinceStepsAndDenseOutputMatchOdeint) {
  const Duffing system;
  const double h = 0.05;
  StepControl control;
  control.fixed_step = h;
  DormandPrince45 ours(control);
  ours.initialize(system, 0.0, State{1.0, 0.0}, {}, 0);

  boost::numeric::odeint::runge_kutta_dopri5<State> peer;
  State x{1.0, 0.0}, dxdt(2), x_new(2), dxdt_new(2), x_mid(2), y_mid(2);
  system(x, dxdt, 0.0);
  double t = 0;
  double worst_state = 0, worst_mid = 0, worst_dense = 0;
  for (int i = 0; i < 200; ++i) {
    peer.do_step(system, x, dxdt, t, x_new, dxdt_new, h);
    ours.step(10.0 + t);  // never truncated: t_max well beyond the step
    for (double frac : {0.25, 0.5, 0.8}) {
      const double tm = t + frac * h;
      peer.calc_state(tm, x_mid, x, dxdt, t, x_new, dxdt_new, t + h);
      ours.dense_output(tm, y_mid);
      for (int k = 0; k < 2; ++k) {
        const double diff = std::fabs(x_mid[k] - y_mid[k]);
        if (frac == 0.5) worst_mid = std::max(worst_mid, diff);
        worst_dense = std::max(worst_dense, diff);
      }
    }
    x = x_new;
    dxdt = dxdt_new;
    t += h;
    for (int k = 0; k < 2; ++k) {
      worst_state = std::max(worst_state, std::fabs(x[k] - ours.current_state()[k]));
    }
  }
  EXPECT_NEAR(ours.current_time(), t, 1e-12);
  EXPECT_LT(worst_state, 1e-12);
  EXPECT_LT(worst_mid, 1e-12);
  EXPECT_LT(worst_dense, 1e-6);  // h^5 = 3e-7
}

TEST(OdeintPeer, Rk4StepsMatchOdeint) {
  const Duffing system;
  const double h = 0.02;
  Rk4 ours(h);
  ours.initialize(system, 0.0, State{0.5, -0.2}, {}, 0);
  boost::numeric::odeint::runge_kutta4<State> peer;
  State x{0.5, -0.2};
  double t = 0, worst = 0;
  for (int i = 0; i < 500; ++i) {
    peer.do_step(system, x, t, h);
    ours.step(10.0 + t);
    t += h;
    for (int k = 0; k < 2; ++k) worst = std::max(worst, std::fabs(x[k] - ours.current_state()[k]));
  }
  EXPECT_LT(worst, 1e-12);
}

}  // namespace
}  // namespace wavebench::model::solver
