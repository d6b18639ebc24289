// PiController: the servo loops' law, against closed forms.
#include "wavebench/model/pi_controller.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

namespace wavebench::model {
namespace {

TEST(PiController, OpenLoopStepIsProportionalPlusRamp) {
  // Constant error e0: u(t) = Kp*e0*(1 + t/Ti), exact in discrete steps too.
  PiController pi(0.5, 0.02);
  PiOutput out;
  for (int i = 0; i < 100; ++i) out = pi.step(2.0, 1e-3);
  EXPECT_NEAR(pi.integral(), 0.2, 1e-12);
  EXPECT_NEAR(out.value, 0.5 * 2.0 * (1 + 0.1 / 0.02), 1e-12);
  EXPECT_FALSE(out.limited);
}

TEST(PiController, CriticallyDampedSpeedLoopMatchesTheClosedForm) {
  // J*w' = u, u = Kp*(e + I/Ti), e = r - w. With Ti = 4J/Kp both poles are at s = -a,
  // a = Kp/(2J), and w(t) = r*(1 - e^(-a t)*(1 - a t)): overshoot e^-2 at t = 2/a.
  const double j = 0.01, kp = 0.2, ti = 4 * j / kp, a = kp / (2 * j), r = 3.0, dt = 1e-5;
  PiController pi(kp, ti);
  double w = 0, peak = 0, peak_t = 0;
  for (int i = 1; i <= 100000; ++i) {
    w += pi.step(r - w, dt).value / j * dt;
    const double t = i * dt;
    if (w > peak) {
      peak = w;
      peak_t = t;
    }
    if (i % 5000 == 0) {
      EXPECT_NEAR(w, r * (1 - std::exp(-a * t) * (1 - a * t)), 2e-3 * r) << "t = " << t;
    }
  }
  EXPECT_NEAR(peak, r * (1 + std::exp(-2.0)), 2e-3 * r);
  EXPECT_NEAR(peak_t, 2 / a, 2e-3);
}

TEST(PiController, ContinuousFormGivesTheStateDerivative) {
  const PiController pi(2.0, 0.5);
  const PiOutput out = pi.evaluate(0.3, 0.1, PiController::kNoLimit, 1.0);
  EXPECT_DOUBLE_EQ(out.value, 1.0 + 2.0 * (0.3 + 0.1 / 0.5));
  EXPECT_DOUBLE_EQ(out.integral_rate, 0.3);
}

TEST(PiController, SaturatedOutputStopsTheIntegralWindingUp) {
  PiController pi(1.0, 0.01);
  PiOutput out;
  for (int i = 0; i < 1000; ++i) out = pi.step(5.0, 1e-3, 2.0);
  EXPECT_TRUE(out.limited);
  EXPECT_DOUBLE_EQ(out.value, 2.0);
  EXPECT_DOUBLE_EQ(pi.integral(), 0.0);  // Kp*e alone is past the limit from the first step
  // The error reverses: the output leaves the limit at once (no wound-up integral to unwind).
  out = pi.step(-1.0, 1e-3, 2.0);
  EXPECT_FALSE(out.limited);
  EXPECT_NEAR(out.value, -1.0 - 1e-3 / 0.01, 1e-12);

  // Integrating towards the limit: I stops once Kp*I/Ti would carry u past it.
  PiController slow(0.1, 0.01);
  for (int i = 0; i < 1000; ++i) out = slow.step(1.0, 1e-3, 2.0);
  EXPECT_TRUE(out.limited);
  EXPECT_LE(slow.integral() * 0.1 / 0.01, 2.0 + 1e-12);
  EXPECT_GE(slow.integral() * 0.1 / 0.01, 2.0 - 0.1 - 0.01);
  // Frozen while limited in the error's direction: the state derivative is 0.
  EXPECT_DOUBLE_EQ(slow.evaluate(1.0, 1.0, 2.0).integral_rate, 0.0);
  EXPECT_DOUBLE_EQ(slow.evaluate(-1.0, 1.0, 0.5).integral_rate, -1.0);
}

TEST(PiController, WithoutIntegralTimeItIsAPLoop) {
  PiController p(120.0, 0);
  const PiOutput out = p.step(0.01, 1.0, 1.0, 0.5);
  EXPECT_DOUBLE_EQ(out.value, 1.0);
  EXPECT_TRUE(out.limited);
  EXPECT_DOUBLE_EQ(p.integral(), 0.0);
  EXPECT_DOUBLE_EQ(p.evaluate(-0.001, 0, 10.0, 0.5).value, 0.5 - 0.12);
  EXPECT_DOUBLE_EQ(p.evaluate(0.001, 0, 0.0).value, 0.0);  // a zero limit allows nothing
}

TEST(PiController, RefusesNegativeOrNonFiniteGains) {
  EXPECT_THROW(PiController(-1, 0), std::invalid_argument);
  EXPECT_THROW(PiController(1, -0.1), std::invalid_argument);
  EXPECT_THROW(PiController(std::nan(""), 0), std::invalid_argument);
  EXPECT_THROW(PiController(1, INFINITY), std::invalid_argument);
}

}  // namespace
}  // namespace wavebench::model
