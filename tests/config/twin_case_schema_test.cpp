// Each section of the schema lands in the right field, in SI.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <variant>

#include "wavebench/config/config_error.hpp"
#include "wavebench/config/twin_case.hpp"

namespace wavebench::config {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kArcsec = kPi / 180.0 / 3600.0;

const std::string kHead = R"(
gear:
  z_flex: 200
  z_circ: 202
  inertia_input: 3e-4
  inertia_output: 0.05
input:
  type: kinematic
  speed: 10
)";

TwinCase parse_with(const std::string& extra) {
  return parse_twin_case(kHead + extra);
}

TEST(TwinCaseSchema, RatioAndWaveNumberFromTeeth) {
  const auto c = parse_with("stiffness: {form: cubic, k1: 1e5, k3: \"1e9 N*m/rad^3\"}\n");
  EXPECT_DOUBLE_EQ(c.gear.geometry.ratio, 100.0);
  EXPECT_EQ(c.gear.geometry.wave_number, 2);
  EXPECT_EQ(c.gear.geometry.direction_sign, 1);
  const auto& law = std::get<model::CubicStiffness>(c.gear.stiffness.law);
  EXPECT_EQ(law.k1, 1e5);
  EXPECT_EQ(law.k3, 1e9);
  EXPECT_DOUBLE_EQ(c.gear.nominal_input_speed, 10.0);
}

TEST(TwinCaseSchema, FourierTermsTakeOrdersFromTheirFamily) {
  const auto c = parse_with(R"(stiffness: {form: linear_periodic, k0: 1e5}
te:
  terms:
    - {source: mesh, family: tooth_mesh, amplitude: "1 arcsec", phase: "90 deg"}
    - {source: once, family: output_once_rev, amplitude: "2 arcmin"}
    - {source: odd, order_input: 3, order_output: -1, amplitude: 1e-6}
)");
  ASSERT_EQ(c.gear.te_terms.size(), 3u);
  const auto& mesh = c.gear.te_terms[0];
  EXPECT_EQ(mesh.family, model::TeFamily::kToothMesh);
  EXPECT_EQ(mesh.order_input, 404.0);
  EXPECT_EQ(mesh.order_output, 0.0);
  EXPECT_DOUBLE_EQ(mesh.amplitude_rad, kArcsec);
  EXPECT_DOUBLE_EQ(mesh.phase_rad, kPi / 2);
  EXPECT_EQ(c.gear.te_terms[1].order_input, 0.0);
  EXPECT_EQ(c.gear.te_terms[1].order_output, 1.0);
  EXPECT_DOUBLE_EQ(c.gear.te_terms[1].amplitude_rad, 120 * kArcsec);
  EXPECT_EQ(c.gear.te_terms[2].family, model::TeFamily::kCustom);
  EXPECT_EQ(c.gear.te_terms[2].order_output, -1.0);
}

TEST(TwinCaseSchema, FamilyAndContradictingOrdersIsAnError) {
  EXPECT_THROW(parse_with(R"(stiffness: {form: linear_periodic, k0: 1e5}
te:
  terms:
    - {source: x, family: housing, order_input: 3, amplitude: 1e-6}
)"),
               ConfigError);
}

TEST(TwinCaseSchema, ErrorSourcesFollowSeed001Formula) {
  const auto c = parse_with(R"(stiffness: {form: linear_periodic, k0: 1e5}
te:
  error_sources:
    pitch_diameter: "80 mm"
    pressure_angle: "20 deg"
    tooth_pairs_in_contact: 2
    sources:
      - {name: dF_i1, tolerance: "10 um", phase: "30 deg"}
      - {name: T1k_1, tolerance: "10 um"}
)");
  ASSERT_EQ(c.gear.te_terms.size(), 2u);
  // theta[arcsec] = 1/(2 N_c) * tol[um] * 412.5296 / d_w[mm]
  const double expected_arcsec = 1.0 / (2 * 2) * 10 * 412.5296 / 80;
  EXPECT_NEAR(c.gear.te_terms[0].amplitude_rad / kArcsec, expected_arcsec, 1e-6);
  EXPECT_EQ(c.gear.te_terms[0].order_input, 2.0);
  EXPECT_EQ(c.gear.te_terms[0].order_output, 2.0);
  EXPECT_DOUBLE_EQ(c.gear.te_terms[0].phase_rad, kPi / 6);
  EXPECT_NEAR(c.gear.te_terms[1].amplitude_rad / kArcsec,
              expected_arcsec / std::cos(20 * kPi / 180), 1e-6);
  EXPECT_NE(c.gear.te_terms[0].source.find("dF_i1"), std::string::npos);
}

TEST(TwinCaseSchema, ThreeSegmentTableAndModulation) {
  const auto c = parse_with(R"(stiffness:
  form: three_segment
  k1: "6.7e4 N*m/rad"
  t1: "29 N*m"
  k2: "1.1e5 N*m/rad"
  t2: "108 N*m"
  k3: "1.2e5 N*m/rad"
  modulation:
    - {amplitude: "5 %", order_input: 2}
)");
  const auto& law = std::get<model::ThreeSegmentStiffness>(c.gear.stiffness.law);
  EXPECT_EQ(law.t2, 108.0);
  ASSERT_EQ(c.gear.stiffness.modulation.size(), 1u);
  EXPECT_DOUBLE_EQ(c.gear.stiffness.modulation[0].amplitude, 0.05);

  const auto t = parse_with(R"(stiffness:
  form: table
  twist: [0, "1 arcmin", "2 arcmin"]
  torque: [0, 10, 25]
)");
  const auto& table = std::get<model::TableStiffness>(t.gear.stiffness.law);
  EXPECT_DOUBLE_EQ(table.twist_rad[2], 120 * kArcsec);
  EXPECT_THROW(parse_with("stiffness: {form: table, twist: [0, 2, 1], torque: [0, 1, 2]}\n"),
               ConfigError);
  EXPECT_THROW(parse_with("stiffness: {form: table, twist: [0, 1, 2], torque: [0, 1]}\n"),
               ConfigError);
}

TEST(TwinCaseSchema, DrivesFrictionLoadSolverAnalysis) {
  const auto c = parse_twin_case(R"(
gear: {ratio: 100, inertia_input: 6.8e-4, inertia_output: 2.4e-2}
stiffness: {form: bouc_wen, k: 1e5, beta: 0.5, gamma: 0.5}
damping: {coefficient: "0.16 N*m*s/rad"}
friction: {model: lugre, sigma0: 500, sigma1: 0.5, coulomb: "50 mN*m", stribeck_speed: 1}
input:
  type: dc_motor
  resistance: "6 Ohm"
  torque_constant: "0.52 N*m/A"
  back_emf_constant: "0.52 V*s/rad"
  voltage: {amplitude: "24 V", frequency: "50 Hz"}
load:
  output_torque: {offset: "10 N*m", amplitude: "2 N*m", frequency: "5 Hz"}
  brake: {rated_torque: "40 N*m", rated_current: "2 A", current: "500 mA", hysteresis: "40 mA"}
solver: {method: rosenbrock, t_end: "250 ms", sample_rate: "20 kHz", rtol: 1e-8}
analysis:
  spectrum: {signal: omega2, window: flattop, max_frequency: "2 kHz"}
  sweep: {from: "100 rpm", to: "2700 rpm", steps: 14, settle_time: 0.5, record_time: 1}
)");
  const auto& m = std::get<model::DcMotorInput>(c.gear.input);
  EXPECT_EQ(m.resistance, 6.0);
  EXPECT_EQ(m.voltage.amplitude, 24.0);
  EXPECT_EQ(m.voltage.frequency_hz, 50.0);
  EXPECT_EQ(m.voltage.offset, 0.0);
  EXPECT_EQ(c.gear.damping.coefficient.value(), 0.16);
  EXPECT_FALSE(c.gear.damping.damping_ratio.has_value());
  const auto& f = std::get<model::LuGreFriction>(c.gear.friction);
  EXPECT_DOUBLE_EQ(f.coulomb, 0.05);
  EXPECT_DOUBLE_EQ(f.static_torque, 0.05);  // defaults to Coulomb
  EXPECT_EQ(c.gear.load.output_torque.offset, 10.0);
  ASSERT_TRUE(c.gear.load.brake.has_value());
  EXPECT_DOUBLE_EQ(c.gear.load.brake_current_a, 0.5);
  EXPECT_DOUBLE_EQ(c.gear.load.brake->rated_torque_nm, 40.0);
  EXPECT_DOUBLE_EQ(c.gear.load.brake->hysteresis_a, 0.04);
  EXPECT_DOUBLE_EQ(c.gear.load.brake->tau_fall_s, c.gear.load.brake->tau_rise_s);
  EXPECT_EQ(c.gear.load.brake->heat_capacity_j_per_k, 0.0);  // no thermal model unless given
  EXPECT_EQ(c.solver.method, model::SolverMethod::kRosenbrock4);
  EXPECT_DOUBLE_EQ(c.solver.t_end, 0.25);
  EXPECT_EQ(c.solver.sample_rate, 20000.0);
  EXPECT_EQ(c.solver.rtol, 1e-8);
  EXPECT_EQ(c.analysis.spectrum.signal, "omega2");
  EXPECT_EQ(c.analysis.spectrum.window, analysis::Window::kFlatTop);
  EXPECT_TRUE(c.analysis.sweep.enabled);
  EXPECT_DOUBLE_EQ(c.analysis.sweep.from_speed, 100 * 2 * kPi / 60);
  EXPECT_DOUBLE_EQ(c.analysis.sweep.to_speed, 2700 * 2 * kPi / 60);
  EXPECT_EQ(c.gear.nominal_input_speed, 0.0);
}

TEST(TwinCaseSchema, OldBrakeKeysAreRefusedNamingTheirReplacement) {
  const auto refused = [](const std::string& brake) -> std::string {
    try {
      parse_with("stiffness: {form: cubic, k1: 1}\nload:\n  brake: " + brake + "\n");
    } catch (const ConfigError& e) {
      return e.what();
    }
    return "accepted";
  };
  const std::string m =
      refused(R"({torque_per_amp: "20 N*m/A", rated_current: "2 A", current: "500 mA"})");
  EXPECT_NE(m.find("load.brake.torque_per_amp"), std::string::npos) << m;
  EXPECT_NE(m.find("rated_torque"), std::string::npos) << m;
  const std::string f = refused(R"({rated_torque: 40, rated_current: 2, falling_ratio: 0.9})");
  EXPECT_NE(f.find("load.brake.falling_ratio"), std::string::npos) << f;
  EXPECT_NE(f.find("hysteresis"), std::string::npos) << f;
  const std::string t = refused(R"({rated_torque: 40, rated_current: 2, tau_rise: 0})");
  EXPECT_NE(t.find("load.brake.tau_rise"), std::string::npos) << t;
  // Hostile values that would keep the twin integrating for ever, or make no brake.
  const std::string tiny = refused(R"({rated_torque: 40, rated_current: 2, tau_fall: "1 ns"})");
  EXPECT_NE(tiny.find("load.brake.tau_fall"), std::string::npos) << tiny;
  const std::string wide = refused(R"({rated_torque: 40, rated_current: 2, hysteresis: "3 A"})");
  EXPECT_NE(wide.find("load.brake.hysteresis"), std::string::npos) << wide;
  const std::string still =
      refused(R"({rated_torque: 40, rated_current: 2, standstill_speed: "1e6 rad/s"})");
  EXPECT_NE(still.find("load.brake.standstill_speed"), std::string::npos) << still;
  EXPECT_EQ(refused(R"({rated_torque: 40, rated_current: 2, tau_fall: "0.2 s"})"), "accepted");
}

TEST(TwinCaseSchema, DampingRatioAndCoefficientTogetherIsAnError) {
  EXPECT_THROW(
      parse_with("stiffness: {form: cubic, k1: 1}\ndamping: {ratio: 0.1, coefficient: 1}\n"),
      ConfigError);
}

}  // namespace
}  // namespace wavebench::config

namespace wavebench::config {
namespace {

// Issue #23 item 3: friction at either shaft; the default is the wave generator's.
TEST(TwinCaseSchema, FrictionSideIsInputUnlessTheCaseSaysOutput) {
  const std::string stiffness = "stiffness: {form: cubic, k1: 1e5, k3: 0}\n";
  EXPECT_EQ(parse_with(stiffness + "friction: {model: coulomb_stribeck, coulomb: 0.1, "
                                   "stribeck_speed: 1}\n")
                .gear.friction_side,
            model::FrictionSide::kInput);
  EXPECT_EQ(parse_with(stiffness + "friction: {model: lugre, side: output, sigma0: 500, "
                                   "coulomb: 0.1, stribeck_speed: 1}\n")
                .gear.friction_side,
            model::FrictionSide::kOutput);
  try {
    parse_with(stiffness +
               "friction: {model: lugre, side: brake, sigma0: 500, coulomb: 0.1, "
               "stribeck_speed: 1}\n");
    FAIL() << "accepted side: brake";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("side"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace wavebench::config
