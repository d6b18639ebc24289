// Memoryless stiffness forms 1-4 (model.md §4).
#include <gtest/gtest.h>

#include <cmath>

#include "wavebench/model/elastic_stiffness.hpp"

namespace wavebench::model {
namespace {

TEST(Stiffness, CatalogueThreeSegmentExample) {
  // model.md §4: size-32 class, 60 N*m gives 7.15e-4 rad (2.46 arcmin).
  const ThreeSegmentStiffness p{6.7e4, 29, 1.1e5, 108, 1.2e5};
  const ThreeSegmentCurve c(p);
  const double x60 = 29 / 6.7e4 + 31 / 1.1e5;
  EXPECT_NEAR(c.twist_at(60), 7.15e-4, 5e-7);
  EXPECT_NEAR(c.twist_at(60), x60, 1e-15);
  EXPECT_NEAR(c.torque(x60), 60, 1e-10);
  EXPECT_NEAR(c.torque(-x60), -60, 1e-10);
  const double x108 = x60 + 48 / 1.1e5;
  EXPECT_NEAR(c.torque(x108 + 1e-4), 108 + 1.2e5 * 1e-4, 1e-9);
  EXPECT_NEAR(c.torque(29 / 6.7e4), 29, 1e-12);
  EXPECT_THROW(ThreeSegmentCurve({6.7e4, 29, 1.1e5, 20, 1.2e5}), std::invalid_argument);
}

TEST(Stiffness, CubicHardeningAndSoftening) {
  StiffnessParams p;
  p.law = CubicStiffness{1e5, 3e11};
  const ElasticStiffness hard(p);
  EXPECT_DOUBLE_EQ(hard.torque(1e-3, 0, 0), 1e5 * 1e-3 + 3e11 * 1e-9);
  EXPECT_DOUBLE_EQ(hard.torque(-1e-3, 0, 0), -hard.torque(1e-3, 0, 0));
  p.law = CubicStiffness{1e5, -3e10};
  EXPECT_LT(ElasticStiffness(p).torque(1e-3, 0, 0), 1e5 * 1e-3);
}

TEST(Stiffness, TableIsMonotoneOddAndThroughThePoints) {
  TableStiffness t;
  t.twist_rad = {0, 1e-4, 2.5e-4, 5e-4, 1e-3};
  t.torque_nm = {0, 5, 20, 45, 100};
  StiffnessParams p;
  p.law = t;
  const ElasticStiffness s(p);
  for (std::size_t i = 0; i < t.twist_rad.size(); ++i) {
    EXPECT_NEAR(s.torque(t.twist_rad[i], 0, 0), t.torque_nm[i], 1e-9);
    EXPECT_NEAR(s.torque(-t.twist_rad[i], 0, 0), -t.torque_nm[i], 1e-9);
  }
  double prev = s.torque(-1.2e-3, 0, 0);
  for (double x = -1.2e-3; x <= 1.2e-3; x += 1e-6) {
    const double v = s.torque(x, 0, 0);
    EXPECT_GE(v, prev - 1e-12) << x;
    prev = v;
  }
  // Linear beyond the last point with the last segment's slope.
  EXPECT_NEAR(s.torque(1.1e-3, 0, 0), 100 + 55 / 5e-4 * 1e-4, 1e-9);
  t.torque_nm[2] = 1;
  p.law = t;
  EXPECT_THROW(ElasticStiffness{p}, std::invalid_argument);
}

TEST(Stiffness, AnglePeriodicForms) {
  StiffnessParams p;
  p.law = LinearPeriodicStiffness{1e5, {{2e4, 2, 2, 0.5}}};
  const ElasticStiffness lin(p);
  const double th1 = 3.1, th2 = 0.4, x = 2e-4;
  EXPECT_NEAR(lin.torque(x, th1, th2), (1e5 + 2e4 * std::cos(2 * th1 + 2 * th2 + 0.5)) * x, 1e-12);
  // A relative modulation multiplies forms 2-4.
  p.law = CubicStiffness{1e5, 1e11};
  p.modulation = {{0.1, 1, 0, 0}};
  const ElasticStiffness cub(p);
  EXPECT_NEAR(cub.torque(x, th1, th2), (1e5 * x + 1e11 * x * x * x) * (1 + 0.1 * std::cos(th1)),
              1e-12);
  EXPECT_DOUBLE_EQ(cub.small_twist_stiffness(), 1e5);
}

}  // namespace
}  // namespace wavebench::model
