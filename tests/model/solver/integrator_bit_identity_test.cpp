// The integrators give, bit for bit, what they gave before they shared IntegratorBase (issue
// #23): a forced damped oscillator through steps, dense output at every step's middle, a landing
// on t_max within rounding, a reset and more steps. The expected values were printed with %a by
// the integrators as they were at commit 9dda5b5 (before the base), on x86-64 (no fused
// multiply-add without -march): a change of the arithmetic of a method shows here first.
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "test_problems.hpp"
#include "wavebench/model/solver/integrators.hpp"

namespace wavebench::model::solver {
namespace {

struct Recorded {
  const char* label;
  double x, v, dense_x_sum, dense_v_sum;
  std::int64_t steps, rejected, rhs, jacobians;
};

constexpr Recorded kBefore[] = {
    {"dp", 0x1.991e10ea30804p-5, -0x1.79c3ac8912515p-3, -0x1.f6d8ad50ebbb7p+0,
     -0x1.7c39b1dfc1ccfp+3, 66, 2, 411, 0},
    {"dpmax", 0x1.991e1043c9003p-5, -0x1.79c3abc95e981p-3, -0x1.4020032ac0f92p+2,
     -0x1.569e3ea63b7f9p+4, 151, 0, 909, 0},
    {"rk4", 0x1.991e0f34a870ap-5, -0x1.79c3b28042dcp-3, -0x1.4920f4f4cf29ep+2,
     -0x1.5719122c3e8a7p+4, 150, 0, 602, 0},
    {"ros", 0x1.991e084866062p-5, -0x1.79c3b12249156p-3, -0x1.483f723a1c8f9p+1,
     -0x1.afa0840c39084p+3, 92, 1, 928, 92},
};

struct Setting {
  IntegratorKind kind;
  Tolerances tolerances;
  double fixed_step, max_step;
};

Setting setting(const std::string& label) {
  if (label == "dp") return {IntegratorKind::kDormandPrince45, {1e-7, 1e-9}, 0, 0};
  if (label == "dpmax") return {IntegratorKind::kDormandPrince45, {1e-7, 1e-9}, 0, 0.01};
  if (label == "rk4") return {IntegratorKind::kRk4, {}, 1e-2, 0};
  return {IntegratorKind::kRosenbrock, {1e-6, 1e-8}, 0, 0};
}

TEST(IntegratorBitIdentity, SameNumbersAsBeforeTheSharedBase) {
#if !defined(__x86_64__)
  GTEST_SKIP() << "values recorded on x86-64";
#endif
  const testing::LinearOscillator system(6.0, 0.05, 3.0, 5.0);
  for (const auto& before : kBefore) {
    SCOPED_TRACE(before.label);
    const auto s = setting(before.label);
    auto in = make_integrator(s.kind, s.tolerances, s.fixed_step, s.max_step);
    const std::vector<double> y0{0.3, -1.0};
    in->initialize(system, 0.0, y0, {}, 0);
    double sum_x = 0, sum_v = 0;
    std::vector<double> y(2);
    while (in->current_time() < 1.0) {
      in->step(1.0);
      in->dense_output(0.5 * (in->previous_time() + in->current_time()), y);
      sum_x += y[0];
      sum_v += y[1];
    }
    in->step(1.0 + 4.5e-16);  // two ulps on: landed on in place, no step taken
    ASSERT_GT(in->current_time(), 1.0);
    const std::vector<double> restart{0.1, 0.2};
    in->reset(in->current_time(), restart);
    while (in->current_time() < 1.5) in->step(1.5);
    const auto state = in->current_state();
    const auto& k = in->counters();
    EXPECT_EQ(state[0], before.x);
    EXPECT_EQ(state[1], before.v);
    EXPECT_EQ(sum_x, before.dense_x_sum);
    EXPECT_EQ(sum_v, before.dense_v_sum);
    EXPECT_EQ(k.steps, before.steps);
    EXPECT_EQ(k.rejected_steps, before.rejected);
    EXPECT_EQ(k.rhs_evaluations, before.rhs);
    EXPECT_EQ(k.jacobian_evaluations, before.jacobians);
  }
}

}  // namespace
}  // namespace wavebench::model::solver
