#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "wavebench/model/simulation.hpp"

namespace wavebench::model {
namespace {

GearGeometry xb80() {
  return {268, 270, 2, 134.0, 1};
}

// Seed 001's formula computed by hand: theta_e[arcsec] = 1/(2 N_c) * (1/cos a) *
// (1/(N cos a)) * T1l * 412.5296 / d_w[mm] for one T1l term.
TEST(ErrorSourceForm, T1lTermMatchesSeedFormulaByHand) {
  ErrorSourceSet set;
  set.pitch_diameter_m = 80.4e-3;
  set.pressure_angle_rad = 20.0 * std::numbers::pi / 180.0;
  set.tooth_pairs_in_contact = 24;
  set.sources = {{"T1l_3", 12e-6, 0.4}};
  const auto terms = te_terms_from_error_sources(set, xb80());
  ASSERT_EQ(terms.size(), 1u);
  const double cos_a = std::cos(20.0 * std::numbers::pi / 180.0);
  const double arcsec =
      1.0 / (2 * 24) * (1.0 / cos_a) * (1.0 / (134.0 * cos_a)) * 12.0 * 412.5296 / 80.4;
  EXPECT_NEAR(terms[0].amplitude_rad * 206264.806, arcsec, 1e-4 * arcsec);
  EXPECT_EQ(terms[0].order_input, 1);
  EXPECT_EQ(terms[0].order_output, 0);
  EXPECT_DOUBLE_EQ(terms[0].phase_rad, 0.4);
  EXPECT_NE(terms[0].source.find("T1l_3"), std::string::npos);
}

TEST(ErrorSourceForm, TangentialCompositeErrorsSitAtTheSideband) {
  ErrorSourceSet set;
  set.pitch_diameter_m = 80.4e-3;
  set.pressure_angle_rad = 0.349;
  set.tooth_pairs_in_contact = 24;
  set.sources = {{"dF_i1", 20e-6, 0}, {"dF_i2", 20e-6, 0}, {"df_i1", 5e-6, 0}};
  const auto terms = te_terms_from_error_sources(set, xb80());
  const double omega1 = 2680.0 * 2 * std::numbers::pi / 60.0;
  EXPECT_NEAR(te_term_frequency_hz(terms[0], xb80(), omega1), 2 * (1 + 1 / 134.0) * 44.6667, 1e-3);
  EXPECT_NEAR(te_term_frequency_hz(terms[1], xb80(), omega1), 89.3333, 1e-3);
  EXPECT_NEAR(te_term_frequency_hz(terms[2], xb80(), omega1), 24120.0, 1e-2);
  // dF terms: 1/(2 N_c) * tol * 412.5296 / d_w arcsec, no angle factor.
  EXPECT_NEAR(terms[0].amplitude_rad * 206264.806, 20.0 * 412.5296 / 80.4 / 48.0, 1e-4);
}

TEST(ErrorSourceForm, UnknownSourceIsRejectedByName) {
  ErrorSourceSet set;
  set.pitch_diameter_m = 0.08;
  set.tooth_pairs_in_contact = 1;
  set.sources = {{"bogus", 1e-6, 0}};
  try {
    te_terms_from_error_sources(set, xb80());
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("bogus"), std::string::npos);
  }
}

}  // namespace
}  // namespace wavebench::model
