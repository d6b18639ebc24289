// SPC of individuals against a hand-worked example (values 1, 2, 3, 5, 4).
#include "wavebench/fleet/spc.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

#include "spc_hand_worked.hpp"

namespace wavebench::fleet {
namespace {

// mean 3; squares 4+1+0+4+1 = 10, sigma = sqrt(10/4) = 1.581139; moving ranges 1, 1, 2, 1:
// MR-bar 1.25, sigma within 1.25/1.128 = 1.108156; UCL 3 + 2.66·1.25 = 6.325, LCL -0.325.
// Limits 0..7: Cp 7/(6·1.25/1.128) = 7.896/7.5 = 1.0528, Cpk min(4, 3)/(3·1.25/1.128) = 0.9024,
// Pp 7/(6·1.581139) = 0.737865, Ppk 3/(3·1.581139) = 0.632456.
TEST(Spc, HandWorkedExample) {
  testing::expect_hand_worked_spc(spc_figures({1, 2, 3, 5, 4}, {0.0, 7.0}));
}

TEST(Spc, OneSidedSpecGivesOnlyItsSide) {
  const auto upper = spc_figures({1, 2, 3, 5, 4}, {std::nullopt, 7.0});
  EXPECT_FALSE(upper.cp);
  EXPECT_FALSE(upper.pp);
  ASSERT_TRUE(upper.cpk);
  EXPECT_NEAR(*upper.cpk, 4 / (3 * 1.108156), 1e-6);
  const auto lower = spc_figures({1, 2, 3, 5, 4}, {0.0, std::nullopt});
  ASSERT_TRUE(lower.ppk);
  EXPECT_NEAR(*lower.ppk, 3 / (3 * 1.581139), 1e-6);
  const auto none = spc_figures({1, 2, 3, 5, 4}, {});
  EXPECT_FALSE(none.cp || none.cpk || none.pp || none.ppk);
}

TEST(Spc, PointOutsideTheIndividualsLimitsIsListed) {
  // Ten values alternating 10.0/10.2, then 13: MR-bar is small, 13 lies above the UCL.
  std::vector<double> v;
  for (int i = 0; i < 10; ++i) v.push_back(i % 2 ? 10.2 : 10.0);
  v.push_back(13.0);
  const auto s = spc_figures(v, {});
  ASSERT_EQ(s.out_of_control.size(), 1u);
  EXPECT_EQ(s.out_of_control[0], 10u);
}

TEST(Spc, RefusesTooFewValuesAndCrossedLimits) {
  EXPECT_THROW(spc_figures({1.0}, {}), std::invalid_argument);
  EXPECT_THROW(spc_figures({1.0, 2.0}, {2.0, 1.0}), std::invalid_argument);
}

TEST(Spc, ConstantValuesGiveNoCapabilityIndex) {
  const auto s = spc_figures({2, 2, 2}, {0.0, 4.0});
  EXPECT_DOUBLE_EQ(s.sigma, 0);
  EXPECT_FALSE(s.cp || s.cpk || s.pp || s.ppk);
  EXPECT_EQ(to_json(s)["cpk"], nullptr);
}

}  // namespace
}  // namespace wavebench::fleet
