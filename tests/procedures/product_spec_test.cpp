// Product specs (configs/specs/*.yaml): read with their units into run limits; a request names
// one by a bounded name that must exist.
#include "wavebench/procedures/product_spec.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "wavebench/procedures/run_limits.hpp"

namespace wavebench::procedures {
namespace {

const std::filesystem::path kShipped =
    std::filesystem::path(WAVEBENCH_SOURCE_DIR) / "configs" / "specs";

TEST(ProductSpec, TheShippedSpecsLoadAndEveryLimitIsARunLimit) {
  const auto names = product_spec_names(kShipped);
  ASSERT_GE(names.size(), 2u);
  for (const auto& name : names) {
    const auto spec = find_product_spec(kShipped, name);
    EXPECT_EQ(spec.name, name);
    EXPECT_FALSE(spec.model.empty()) << name;
    EXPECT_FALSE(spec.limits.empty()) << name;
    EXPECT_NO_THROW(validate_limits(spec.run_limits())) << name;
  }
}

TEST(ProductSpec, UnitsAreConvertedToTheUnitsOfTheLimitKeys) {
  const auto spec = parse_product_spec(
      "model: X\nlimits:\n  static_te_p2p: 60 arcsec\n  min_k1: 1 N*m/arcmin\n"
      "  dynamic_te_p2p: 1 arcmin\n  twin_residual_rms: 2 arcsec\n  lost_motion: 0.5 arcmin\n"
      "  lost_motion_at: 4 %\n",
      "x", "x.yaml");
  const auto limits = spec.run_limits();
  EXPECT_NEAR(limits["static_p2p_arcmin"].get<double>(), 1.0, 1e-12);
  EXPECT_NEAR(limits["min_stiffness_nm_per_rad"].get<double>(), 10800 / M_PI, 1e-6);
  EXPECT_NEAR(limits["dynamic_p2p_arcsec"].get<double>(), 60.0, 1e-9);
  EXPECT_NEAR(limits["twin_residual_rms_arcsec"].get<double>(), 2.0, 1e-12);
  EXPECT_NEAR(limits["lost_motion_arcmin"].get<double>(), 0.5, 1e-12);
  ASSERT_TRUE(spec.lost_motion_fraction.has_value());
  EXPECT_NEAR(*spec.lost_motion_fraction, 0.04, 1e-15);
  const auto j = spec.to_json();
  EXPECT_EQ(j["limits"][0]["key"], "static_te_p2p");
  EXPECT_EQ(j["limits"][0]["unit"], "arcmin");
  EXPECT_NEAR(j["lost_motion_at_percent"].get<double>(), 4.0, 1e-12);
  // Written values read back as written, not with the unit round trip's last bit.
  EXPECT_EQ(find_product_spec(kShipped, "sim-seed004").run_limits()["static_p2p_arcmin"], 7.0);
}

TEST(ProductSpec, TheTwinResidualLimitChecksTheCalibratedTwinsResidual) {
  const nlohmann::json results = {
      {"twin",
       {{"residual", {{"rms_arcsec", 100.0}}}, {"calibration", {{"rms_after_arcsec", 3.0}}}}}};
  const auto pass = check_limits({{"twin_residual_rms_arcsec", 4.0}}, results);
  ASSERT_TRUE(pass.pass.has_value());
  EXPECT_TRUE(*pass.pass);
  const auto fail = check_limits({{"twin_residual_rms_arcsec", 2.5}}, results);
  ASSERT_TRUE(fail.pass.has_value());
  EXPECT_FALSE(*fail.pass);
  EXPECT_EQ(fail.checks[0]["limit"], "twin_residual_rms_arcsec");
  EXPECT_FALSE(
      check_limits({{"twin_residual_rms_arcsec", 2.5}}, nlohmann::json::object()).pass.has_value());
  // Without a calibration the limit does not apply: the nominal residual is another quantity.
  const nlohmann::json uncalibrated = {{"twin", {{"residual", {{"rms_arcsec", 1.0}}}}}};
  EXPECT_FALSE(check_limits({{"twin_residual_rms_arcsec", 2.5}}, uncalibrated).pass.has_value());
}

TEST(ProductSpec, AnUnknownNameIsRefusedListingTheKnownSpecs) {
  try {
    find_product_spec(kShipped, "csf-25-101");
    FAIL() << "accepted";
  } catch (const std::invalid_argument& e) {
    const std::string m = e.what();
    EXPECT_EQ(m.rfind("spec: got 'csf-25-101', expected one of the known specs: ", 0), 0u) << m;
    EXPECT_NE(m.find("csf-25-100"), std::string::npos) << m;
    EXPECT_NE(m.find("sim-seed004"), std::string::npos) << m;
  }
}

}  // namespace
}  // namespace wavebench::procedures
