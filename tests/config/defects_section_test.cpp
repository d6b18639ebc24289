// The `defects:` section of a gear case (the simulated unit's defects, issue #11): what it
// reads, and each refusal names the key, the value and what was expected.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "wavebench/config/config_error.hpp"
#include "wavebench/config/twin_case.hpp"

namespace wavebench::config {
namespace {

constexpr double kArcmin = std::numbers::pi / (180.0 * 60.0);

const std::string kGear = R"(
name: unit with defects
gear:
  z_flex: 200
  z_circ: 202
  inertia_input: "3.0e-4 kg*m^2"
  inertia_output: "0.05 kg*m^2"
stiffness:
  form: linear_periodic
  k0: "3.0e4 N*m/rad"
input:
  type: kinematic
  speed: "100 rpm"
)";

ConfigError expect_refused(const std::string& defects, const std::string& key,
                           const std::string& value) {
  try {
    parse_twin_case(kGear + defects, "unit.yaml");
  } catch (const ConfigError& e) {
    const std::string msg = e.what();
    EXPECT_EQ(e.key(), key) << msg;
    EXPECT_EQ(e.value(), value) << msg;
    EXPECT_NE(msg.find(key), std::string::npos) << msg;
    EXPECT_FALSE(e.expected().empty()) << msg;
    return e;
  }
  ADD_FAILURE() << "no ConfigError for " << key;
  return ConfigError("", "", "");
}

TEST(DefectsSection, ReadsToothDefectsAndARisingOncePerRev) {
  const auto c = parse_twin_case(kGear + R"(
defects:
  - {kind: tooth, part: flexspline, tooth: 37, amplitude: "0.5 arcmin", width: 0.2}
  - {kind: tooth, part: circular_spline, amplitude: "-0.3 arcmin", onset: "2.5 rev"}
  - {kind: rising_once_per_rev, growth_per_rev: "0.1 arcmin", phase: "30 deg", onset: "3 rev"}
)");
  const auto& d = c.gear.defects;
  ASSERT_EQ(d.teeth.size(), 2u);
  EXPECT_EQ(d.teeth[0].part, model::DefectPart::kFlexspline);
  EXPECT_EQ(d.teeth[0].tooth, 37);
  EXPECT_NEAR(d.teeth[0].amplitude_rad, 0.5 * kArcmin, 1e-12);
  EXPECT_DOUBLE_EQ(d.teeth[0].width, 0.2);
  EXPECT_DOUBLE_EQ(d.teeth[0].onset_rev, 0);
  EXPECT_EQ(d.teeth[1].part, model::DefectPart::kCircularSpline);
  EXPECT_EQ(d.teeth[1].tooth, 0);
  EXPECT_DOUBLE_EQ(d.teeth[1].width, 0.5);
  EXPECT_NEAR(d.teeth[1].onset_rev, 2.5, 1e-12);
  ASSERT_EQ(d.rising_once_per_rev.size(), 1u);
  EXPECT_NEAR(d.rising_once_per_rev[0].growth_rad_per_rev, 0.1 * kArcmin, 1e-12);
  EXPECT_NEAR(d.rising_once_per_rev[0].phase_rad, std::numbers::pi / 6, 1e-12);
  EXPECT_NEAR(d.rising_once_per_rev[0].onset_rev, 3, 1e-12);
}

TEST(DefectsSection, WithoutOneTheGearHasNoDefects) {
  EXPECT_TRUE(parse_twin_case(kGear).gear.defects.empty());
}

TEST(DefectsSection, RefusesAnUnknownKindPartToothOrKey) {
  expect_refused("defects:\n  - {kind: crack, part: flexspline, amplitude: \"1 arcsec\"}\n",
                 "defects[0].kind", "crack");
  expect_refused("defects:\n  - {kind: tooth, part: wave_generator, amplitude: \"1 arcsec\"}\n",
                 "defects[0].part", "wave_generator");
  expect_refused(
      "defects:\n  - {kind: tooth, part: flexspline, tooth: 200, amplitude: \"1 arcsec\"}\n",
      "defects[0].tooth", "200");
  expect_refused(
      "defects:\n  - {kind: tooth, part: flexspline, amplitude: \"1 arcsec\", size: 3}\n",
      "defects[0].size", "3");
}

TEST(DefectsSection, RefusesAZeroOrHugeAmplitudeAWidthOutsideZeroToOneAndANegativeOnset) {
  expect_refused("defects:\n  - {kind: tooth, part: flexspline, amplitude: 0}\n",
                 "defects[0].amplitude", "0");
  expect_refused("defects:\n  - {kind: tooth, part: flexspline, amplitude: \"2 deg\"}\n",
                 "defects[0].amplitude", "2 deg");
  expect_refused(
      "defects:\n  - {kind: tooth, part: flexspline, amplitude: \"1 arcsec\", width: 1.5}\n",
      "defects[0].width", "1.5");
  expect_refused(
      "defects:\n  - {kind: tooth, part: flexspline, amplitude: \"1 arcsec\", onset: \"-1 rev\"}\n",
      "defects[0].onset", "-1 rev");
  expect_refused("defects:\n  - {kind: rising_once_per_rev, growth_per_rev: \"3 N*m\"}\n",
                 "defects[0].growth_per_rev", "3 N*m");
}

TEST(DefectsSection, AToothNeedsTheTeethOfItsPart) {
  std::string gear = kGear;
  const std::string teeth = "  z_flex: 200\n  z_circ: 202\n";
  gear.replace(gear.find(teeth), teeth.size(), "  ratio: 100\n");
  try {
    parse_twin_case(
        gear + "defects:\n  - {kind: tooth, part: flexspline, amplitude: \"1 arcsec\"}\n",
        "unit.yaml");
    ADD_FAILURE() << "a tooth defect without z_flex was taken";
  } catch (const ConfigError& e) {
    EXPECT_EQ(e.key(), "defects[0].part") << e.what();
    EXPECT_NE(std::string(e.what()).find("z_flex"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace wavebench::config
