// The GUM budget arithmetic and the ISO 14253-1 decision against a limit.
#include "wavebench/metrology/uncertainty_budget.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace wavebench::metrology {
namespace {

TEST(UncertaintyBudget, QuantisationIsTheStdOfAUniformOverOneStep) {
  const double q = 2 * M_PI / 1048576;
  EXPECT_DOUBLE_EQ(quantisation_standard(q), q / std::sqrt(12.0));
  // Independently: the spread of rounding errors of many values.
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> any(0, 1000 * q);
  double ss = 0;
  const int n = 200000;
  for (int i = 0; i < n; ++i) {
    const double x = any(rng);
    const double e = std::round(x / q) * q - x;
    ss += e * e;
  }
  EXPECT_NEAR(std::sqrt(ss / n), quantisation_standard(q), 0.01 * quantisation_standard(q));
}

TEST(UncertaintyBudget, CombinesByRootSumOfSquaresAndExpandsWithK2) {
  UncertainFigure f{5.7, {}};
  f.add("a", 0.03).add("b", -0.04, 'A');
  EXPECT_DOUBLE_EQ(f.combined_standard(), 0.05);
  EXPECT_DOUBLE_EQ(f.expanded(), 0.1);
  const auto j = to_json(f, 2.0);
  EXPECT_DOUBLE_EQ(j["value"].get<double>(), 11.4);
  EXPECT_DOUBLE_EQ(j["expanded"].get<double>(), 0.2);
  EXPECT_EQ(j["budget"][1]["type"], "A");
  EXPECT_DOUBLE_EQ(j["budget"][1]["standard"].get<double>(), 0.08);
}

TEST(UncertaintyBudget, SpreadOfRepeats) {
  EXPECT_DOUBLE_EQ(sample_std({1.0}), 0.0);
  EXPECT_DOUBLE_EQ(sample_std({1.0, 3.0}), std::sqrt(2.0));
  EXPECT_DOUBLE_EQ(standard_of_mean(2.0, 4), 1.0);
  EXPECT_DOUBLE_EQ(standard_of_mean(2.0, 1), 0.0);
  EXPECT_DOUBLE_EQ(rectangular_standard(std::sqrt(3.0)), 1.0);
}

TEST(UncertaintyBudget, GuardBandedDecisionsAgainstALimit) {
  UncertainFigure f{5.98, {}};
  f.add("noise", 0.02);  // U = 0.04: interval [5.94, 6.02]
  EXPECT_EQ(decide_upper_limit(f, 6.0), LimitDecision::kUndecided);
  EXPECT_EQ(decide_upper_limit(f, 6.05), LimitDecision::kPass);
  EXPECT_EQ(decide_upper_limit(f, 5.9), LimitDecision::kFail);
  EXPECT_EQ(decide_lower_limit(f, 5.9), LimitDecision::kPass);
  EXPECT_EQ(decide_lower_limit(f, 6.0), LimitDecision::kUndecided);
  EXPECT_EQ(decide_lower_limit(f, 6.1), LimitDecision::kFail);
  EXPECT_STREQ(decision_name(LimitDecision::kUndecided), "UNDECIDED");
}

}  // namespace
}  // namespace wavebench::metrology
