// scale_stiffness (model.md §4): one definition for the simulated unit's variation and the
// twin calibration, checked against values worked out by hand.
#include "wavebench/model/stiffness_scaling.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "wavebench/model/elastic_stiffness.hpp"
#include "wavebench/model/fading_memory_spring.hpp"

namespace wavebench::model {
namespace {

TEST(StiffnessScaling, CatalogueTwiceAsStiffHalvesTheTwistAtEveryTorque) {
  // model.md §4 size-32 example: 60 N*m twists 29/6.7e4 + 31/1.1e5 = 7.1465e-4 rad.
  StiffnessParams s;
  s.law = ThreeSegmentStiffness{6.7e4, 29, 1.1e5, 108, 1.2e5};
  s.mean_stiffness = 7.8e5;
  scale_stiffness(s, 2.0);
  const ThreeSegmentCurve curve(std::get<ThreeSegmentStiffness>(s.law));
  EXPECT_NEAR(curve.twist_at(60), (29 / 6.7e4 + 31 / 1.1e5) / 2, 1e-15);
  EXPECT_NEAR(curve.twist_at(150), (29 / 6.7e4 + 79 / 1.1e5 + 42 / 1.2e5) / 2, 1e-15);
  EXPECT_DOUBLE_EQ(*s.mean_stiffness, 1.56e6);
}

TEST(StiffnessScaling, CubicGivesFTimesTheTorqueAtTheSameTwist) {
  StiffnessParams s;
  s.law = CubicStiffness{1e5, 3e11};
  scale_stiffness(s, 0.5);
  // 0.5 * (1e5 * 1e-3 + 3e11 * 1e-9) = 0.5 * 400 = 200 N*m.
  EXPECT_NEAR(ElasticStiffness(s).torque_unmodulated(1e-3), 200, 1e-9);
}

TEST(StiffnessScaling, FadingMemoryScalesItsMemoryTorqueToo) {
  // Seed 003 values. Twist ramped at v for long (t >> 1/B): z settles at A*v/B, so
  // T = a x^3 + b x^2 + c x + A v / B. With x = 1e-3 rad, v = 3e-3 rad/s:
  // 0.12e-9 + 0.56e-6 + 52 + 40000 * 3e-3 / 300 = 52.4000005601 N*m; f = 3 gives 157.2000016803.
  StiffnessParams s;
  s.law = FadingMemoryStiffness{0.12, 0.56, 52000, 40000, 300};
  scale_stiffness(s, 3.0);
  const auto& p = std::get<FadingMemoryStiffness>(s.law);
  const FadingMemorySpring spring(p);
  const double v = 3e-3;
  const double z_settled = p.memory_gain * v / p.memory_decay;
  EXPECT_NEAR(spring.memory_rate(v, z_settled), 0, 1e-12);  // z is where the memory settles
  EXPECT_NEAR(spring.torque(1e-3, z_settled), 3 * 52.4000005601, 1e-9);
  EXPECT_DOUBLE_EQ(p.memory_decay, 300);  // a time constant: not a stiffness
}

TEST(StiffnessScaling, LinearPeriodicTableAndHysteresisScaleEveryStiffnessTerm) {
  StiffnessParams s;
  s.law = LinearPeriodicStiffness{2e5, {{1e4, 2, 0, 0.3}}};
  s.modulation = {{0.05, 2, 0, 0}};
  scale_stiffness(s, 2.0);
  const auto& l = std::get<LinearPeriodicStiffness>(s.law);
  EXPECT_DOUBLE_EQ(l.k0, 4e5);
  EXPECT_DOUBLE_EQ(l.harmonics[0].amplitude, 2e4);
  EXPECT_DOUBLE_EQ(l.harmonics[0].phase_rad, 0.3);
  EXPECT_DOUBLE_EQ(s.modulation[0].amplitude, 0.05);  // relative: unchanged

  s.law = TableStiffness{{0, 1e-4, 1e-3}, {0, 5, 100}};
  s.mean_stiffness.reset();
  scale_stiffness(s, 2.0);
  EXPECT_NEAR(ElasticStiffness(s).torque_unmodulated(1e-4), 10, 1e-12);
  EXPECT_FALSE(s.mean_stiffness.has_value());

  s.law = HystereticBranchStiffness{1, 2, 3, 4, 5, 6};
  scale_stiffness(s, 2.0);
  const auto& h = std::get<HystereticBranchStiffness>(s.law);
  EXPECT_DOUBLE_EQ(h.a_load + h.b_load + h.c_load + h.a_unload + h.b_unload + h.c_unload, 42);

  s.law = BoucWenStiffness{1e5, 0.5, 1, 1, 1};
  scale_stiffness(s, 2.0);
  EXPECT_DOUBLE_EQ(std::get<BoucWenStiffness>(s.law).k, 2e5);
}

TEST(StiffnessScaling, RefusesANonPositiveFactor) {
  StiffnessParams s;
  s.law = CubicStiffness{1e5, 0};
  EXPECT_THROW(scale_stiffness(s, 0.0), std::invalid_argument);
  EXPECT_THROW(scale_stiffness(s, -1.0), std::invalid_argument);
  EXPECT_THROW(scale_stiffness(s, std::nan("")), std::invalid_argument);
}

}  // namespace
}  // namespace wavebench::model
