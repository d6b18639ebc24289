#pragma once
// The SPC figures of the values {1, 2, 3, 5, 4} with LSL 0 and USL 7, worked by hand (mean 3,
// MR-bar 1.25, σ_within = MR-bar / 1.128, limits mean ± 2.66 MR-bar): checked against
// spc_figures() and against every store's SPC answer.
#include <gtest/gtest.h>

#include "wavebench/fleet/spc.hpp"

namespace wavebench::fleet::testing {

inline void expect_hand_worked_spc(const SpcFigures& s) {
  EXPECT_EQ(s.n, 5u);
  EXPECT_DOUBLE_EQ(s.mean, 3.0);
  EXPECT_NEAR(s.sigma, 1.581139, 1e-6);
  EXPECT_DOUBLE_EQ(s.mr_bar, 1.25);
  EXPECT_NEAR(s.sigma_within, 1.108156, 1e-6);
  EXPECT_NEAR(s.ucl, 6.325, 1e-12);
  EXPECT_NEAR(s.lcl, -0.325, 1e-12);
  ASSERT_TRUE(s.cp && s.cpk && s.pp && s.ppk);
  EXPECT_NEAR(*s.cp, 1.0528, 1e-12);
  EXPECT_NEAR(*s.cpk, 0.9024, 1e-12);
  EXPECT_NEAR(*s.pp, 0.737865, 1e-6);
  EXPECT_NEAR(*s.ppk, 0.632456, 1e-6);
  EXPECT_TRUE(s.out_of_control.empty());
}

}  // namespace wavebench::fleet::testing
