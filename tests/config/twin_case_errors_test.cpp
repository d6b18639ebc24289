// One test per class of config error: each asserts the message names the key and the value.
#include <gtest/gtest.h>

#include <string>

#include "wavebench/config/config_error.hpp"
#include "wavebench/config/twin_case.hpp"

namespace wavebench::config {
namespace {

// A small valid case; each test breaks one thing in it.
const std::string kValid = R"(
name: minimal
gear:
  z_flex: 268
  z_circ: 270
  ratio: 134
  inertia_input: "2.2e-4 kg*m^2"
  inertia_output: "0.2839 kg*m^2"
stiffness:
  form: linear_periodic
  k0: "2.0e5 N*m/rad"
input:
  type: kinematic
  speed: "2680 rpm"
)";

std::string replaced(const std::string& from, const std::string& to) {
  std::string s = kValid;
  const auto pos = s.find(from);
  EXPECT_NE(pos, std::string::npos) << from;
  s.replace(pos, from.size(), to);
  return s;
}

// Parses `yaml`, expects a ConfigError at `key` whose message holds `key` and `value`.
ConfigError expect_error(const std::string& yaml, const std::string& key,
                         const std::string& value) {
  try {
    parse_twin_case(yaml, "case.yaml");
  } catch (const ConfigError& e) {
    const std::string msg = e.what();
    EXPECT_EQ(e.key(), key) << msg;
    EXPECT_EQ(e.value(), value) << msg;
    EXPECT_NE(msg.find(key), std::string::npos) << msg;
    EXPECT_NE(msg.find("'" + value + "'"), std::string::npos) << msg;
    EXPECT_NE(msg.find("case.yaml"), std::string::npos) << msg;
    EXPECT_FALSE(e.expected().empty());
    return e;
  }
  ADD_FAILURE() << "no ConfigError for key " << key;
  return ConfigError("", "", "");
}

TEST(TwinCaseErrors, ValidBaseParses) {
  const TwinCase c = parse_twin_case(kValid);
  EXPECT_EQ(c.gear.geometry.ratio, 134.0);
}

TEST(TwinCaseErrors, MissingRequiredKey) {
  const auto e = expect_error(replaced("  inertia_output: \"0.2839 kg*m^2\"\n", ""),
                              "gear.inertia_output", "");
  EXPECT_NE(e.expected().find("required"), std::string::npos);
  expect_error(replaced("stiffness:\n  form: linear_periodic\n  k0: \"2.0e5 N*m/rad\"\n", ""),
               "stiffness", "");
}

TEST(TwinCaseErrors, UnknownUnit) {
  const auto e = expect_error(replaced("2.0e5 N*m/rad", "2.0e5 N*m/furlong"), "stiffness.k0",
                              "2.0e5 N*m/furlong");
  EXPECT_NE(e.expected().find("unknown unit"), std::string::npos);
  EXPECT_NE(e.expected().find("N*m/arcmin"), std::string::npos);
}

TEST(TwinCaseErrors, UnitOfWrongDimension) {
  const auto e = expect_error(replaced("2.0e5 N*m/rad", "2.0e5 N*m"), "stiffness.k0", "2.0e5 N*m");
  EXPECT_NE(e.expected().find("torque"), std::string::npos) << e.what();
  expect_error(replaced("2680 rpm", "2680 mm"), "input.speed", "2680 mm");
}

TEST(TwinCaseErrors, NonPositiveInertia) {
  expect_error(replaced("2.2e-4 kg*m^2", "-2.2e-4 kg*m^2"), "gear.inertia_input", "-2.2e-4 kg*m^2");
  expect_error(replaced("\"0.2839 kg*m^2\"", "0"), "gear.inertia_output", "0");
}

TEST(TwinCaseErrors, RatioInconsistentWithToothCounts) {
  const auto e = expect_error(replaced("ratio: 134", "ratio: 135"), "gear.ratio", "135");
  EXPECT_NE(e.expected().find("134"), std::string::npos) << e.what();
  expect_error(replaced("z_circ: 270", "z_circ: 268"), "gear.z_circ", "268");
}

TEST(TwinCaseErrors, NonFiniteValue) {
  expect_error(replaced("\"2.0e5 N*m/rad\"", ".nan"), "stiffness.k0", ".nan");
  expect_error(replaced("\"2680 rpm\"", ".inf"), "input.speed", ".inf");
  expect_error(replaced("2680 rpm", "inf rpm"), "input.speed", "inf rpm");
}

TEST(TwinCaseErrors, UnknownKeyIsATypoWithASuggestion) {
  const auto e =
      expect_error(replaced("  z_flex: 268", "  z_flx: 268\n  z_flex: 268"), "gear.z_flx", "268");
  EXPECT_NE(e.expected().find("z_flex"), std::string::npos) << e.what();
  expect_error(kValid + "solvr:\n  t_end: 1\n", "solvr", "{t_end: 1}");
}

TEST(TwinCaseErrors, UnknownChoice) {
  const auto e = expect_error(replaced("form: linear_periodic", "form: quadratic"),
                              "stiffness.form", "quadratic");
  EXPECT_NE(e.expected().find("bouc_wen"), std::string::npos);
}

TEST(TwinCaseErrors, MalformedYamlNamesTheLine) {
  try {
    parse_twin_case("gear: [1, 2\nstiffness: {", "broken.yaml");
    FAIL();
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("broken.yaml"), std::string::npos);
    EXPECT_NE(e.value().find("line"), std::string::npos);
  }
}

TEST(TwinCaseErrors, UnknownErrorSourceName) {
  const std::string yaml = kValid + R"(te:
  error_sources:
    pitch_diameter: "80 mm"
    pressure_angle: "20 deg"
    tooth_pairs_in_contact: 6
    sources:
      - {name: dF_i1, tolerance: "10 um"}
      - {name: dX_9, tolerance: "10 um"}
)";
  expect_error(yaml, "te.error_sources.sources[1].name", "dX_9");
}

TEST(TwinCaseErrors, ToleranceWithoutUnitIsNotTakenAsMetres) {
  const std::string yaml = kValid + R"(te:
  error_sources:
    pitch_diameter: "80 mm"
    pressure_angle: "20 deg"
    tooth_pairs_in_contact: 6
    sources:
      - {name: dF_i1, tolerance: 12}
)";
  const auto e = expect_error(yaml, "te.error_sources.sources[0].tolerance", "12");
  EXPECT_NE(e.expected().find("um"), std::string::npos);
}

TEST(TwinCaseErrors, MissingFileIsAConfigError) {
  EXPECT_THROW(load_twin_case("/nonexistent/case.yaml"), ConfigError);
}

TEST(TwinCaseErrors, TransientNotShorterThanRun) {
  expect_error(kValid + "solver:\n  t_end: 1 s\n  transient: 2 s\n", "solver.transient", "2 s");
}

}  // namespace
}  // namespace wavebench::config
