// Linearised two-inertia model: closed-form natural frequency, damping, transfer functions and
// seed 003's G(s) derived from its equations of motion (the seed's printed G(s) has typos: a
// spurious N in the s^2 term and a constant term K(KN - K)R that cannot exist, since nothing
// ties the drive train to the ground).
#include "wavebench/analysis/linearised_gear.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <complex>
#include <numbers>

namespace wa = wavebench::analysis;
namespace wm = wavebench::model;
using cd = std::complex<double>;

namespace {

wm::GearParams seed003() {
  wm::GearParams p;
  p.geometry.ratio = 100;
  p.inertia_input = 6.8e-4;
  p.inertia_output = 2.4e-2;
  p.viscous_input = 0.003;
  p.viscous_output = 0.005;
  p.stiffness.law = wm::LinearPeriodicStiffness{7.8e5, {}};
  p.damping.coefficient = 0.16;
  wm::DcMotorInput dc;
  dc.resistance = 6;
  dc.torque_constant = 0.52;
  dc.back_emf_constant = 0.52;
  dc.voltage = {0, 24, 50, 0};
  p.input = dc;
  return p;
}

wa::DcMotorGearConstants seed003_constants(double mesh_damping, double cj, double cz) {
  wa::DcMotorGearConstants k;
  k.resistance = 6;
  k.torque_constant = 0.52;
  k.back_emf_constant = 0.52;
  k.inertia_motor = 6.8e-4;
  k.inertia_load = 2.4e-2;
  k.damping_motor = cj;
  k.damping_load = cz;
  k.mesh_damping = mesh_damping;
  k.stiffness = 7.8e5;
  k.ratio = 100;
  return k;
}

}  // namespace

TEST(LinearisedGear, NaturalFrequencyIsSqrtKOverJeq) {
  auto p = seed003();
  p.viscous_input = p.viscous_output = 0;
  p.damping.coefficient = 0;
  p.input = wm::TorqueInput{};
  const auto gear = wa::linearise_gear(p, 0.0);
  ASSERT_EQ(gear.modes.size(), 1u);  // the rigid-body mode is left out
  const double n2j1 = 1e4 * 6.8e-4;
  const double jeq = n2j1 * 2.4e-2 / (n2j1 + 2.4e-2);
  const double expected = std::sqrt(7.8e5 / jeq) / (2 * std::numbers::pi);
  EXPECT_NEAR(gear.modes[0].natural_frequency_hz, expected, 1e-9 * expected);
  EXPECT_NEAR(gear.modes[0].natural_frequency_hz, 909.0, 1.0);
  EXPECT_NEAR(gear.modes[0].damping_ratio, 0.0, 1e-12);
  // Mode shape: input (referred to the output) and output swing against each other with
  // amplitudes in the inverse ratio of their inertias.
  EXPECT_LT(gear.modes[0].shape_input * gear.modes[0].shape_output, 0);
  EXPECT_NEAR(std::abs(gear.modes[0].shape_input / gear.modes[0].shape_output), 2.4e-2 / n2j1,
              1e-9);
}

TEST(LinearisedGear, DampingRatioGivenIsRecovered) {
  auto p = seed003();
  p.viscous_input = p.viscous_output = 0;
  p.damping.coefficient.reset();
  p.damping.damping_ratio = 0.06;
  p.input = wm::TorqueInput{};
  const auto gear = wa::linearise_gear(p, 0.0);
  ASSERT_EQ(gear.modes.size(), 1u);
  EXPECT_NEAR(gear.modes[0].damping_ratio, 0.06, 1e-9);
}

TEST(LinearisedGear, KinematicInputLeavesOneModeOnTheOutput) {
  auto p = seed003();
  p.input = wm::KinematicInput{100, 0, {}, {}};
  p.viscous_output = 0;
  const auto gear = wa::linearise_gear(p, 0.0);
  ASSERT_EQ(gear.modes.size(), 1u);
  const double wn = std::sqrt(7.8e5 / 2.4e-2);
  EXPECT_NEAR(gear.modes[0].natural_frequency_hz, wn / (2 * std::numbers::pi), 1e-9);
  EXPECT_NEAR(gear.modes[0].damping_ratio, 0.16 / (2 * 2.4e-2 * wn), 1e-12);
  // TE -> output angle: -(K + c s) / (J2 s^2 + c s + K); unity (in magnitude) far below wn.
  const auto& co = gear.coefficients;
  const cd s(0, 2 * std::numbers::pi * 300);
  const cd expected = -(7.8e5 + 0.16 * s) / (2.4e-2 * s * s + 0.16 * s + 7.8e5);
  EXPECT_NEAR(std::abs(wa::te_transfer(co, "theta2_dev", 300) - expected), 0, 1e-12);
  EXPECT_NEAR(std::abs(wa::te_transfer(co, "alpha2", 300) - s * s * expected), 0,
              1e-9 * std::abs(s * s));
  EXPECT_NEAR(std::abs(wa::te_transfer(co, "theta2_dev", 0.01) + 1.0), 0, 1e-6);
  // The twist vanishes at low frequency: the output follows the kinematic error.
  EXPECT_LT(std::abs(wa::te_transfer(co, "twist", 0.01)), 1e-6);
  EXPECT_THROW(wa::te_transfer(co, "load_torque", 10), std::invalid_argument);
}

TEST(LinearisedGear, DcMotorBackEmfIsInputDamping) {
  const auto gear = wa::linearise_gear(seed003(), 0.0);
  EXPECT_NEAR(gear.coefficients.damping_input, 0.003 + 0.52 * 0.52 / 6, 1e-12);
  EXPECT_DOUBLE_EQ(gear.coefficients.mesh_damping, 0.16);
}

TEST(LinearisedGear, TwoInertiaTransferMatchesDirectSolve) {
  const auto gear = wa::linearise_gear(seed003(), 0.0);
  const auto& co = gear.coefficients;
  const double f = 700;
  const cd s(0, 2 * std::numbers::pi * f);
  // Independent: eliminate by hand. Unknowns q1 (theta1), q2 (theta2) for e = 1.
  const double n = 100, k = 7.8e5, c = 0.16;
  const cd g = k + c * s;
  const cd a11 = 6.8e-4 * s * s + co.damping_input * s + g / (n * n);
  const cd a12 = -g / n;
  const cd a22 = 2.4e-2 * s * s + 0.005 * s + g;
  const cd f1 = g / n, f2 = -g;
  const cd det = a11 * a22 - a12 * a12;
  const cd q1 = (f1 * a22 - a12 * f2) / det;
  const cd q2 = (a11 * f2 - a12 * f1) / det;
  EXPECT_NEAR(std::abs(wa::te_transfer(co, "theta2_dev", f) - q2), 0, 1e-9 * std::abs(q2));
  EXPECT_NEAR(std::abs(wa::te_transfer(co, "te", f) - (q2 - q1 / n)), 0, 1e-9);
  const cd twist = q1 / n - q2 - 1.0;
  EXPECT_NEAR(std::abs(wa::te_transfer(co, "gear_torque", f) - g * twist), 0,
              1e-9 * std::abs(g * twist));
}

TEST(Seed003TransferFunction, UndampedCoefficientsFromTheEquations) {
  // G(s) = K Km N / (Jj Jz N^2 R s^4 + Jz Ke Km N^2 s^3 + K R (Jj N^2 + Jz) s^2 + K Ke Km N^2 s)
  const auto g = wa::dc_motor_output_angle_transfer(seed003_constants(0, 0, 0));
  const double K = 7.8e5, Km = 0.52, Ke = 0.52, N = 100, R = 6, Jj = 6.8e-4, Jz = 2.4e-2;
  ASSERT_EQ(g.numerator.coefficients.size(), 1u);
  EXPECT_NEAR(g.numerator.coefficients[0], K * Km * N, 1e-9 * K * Km * N);
  const std::vector<double> expected{Jj * Jz * N * N * R, Jz * Ke * Km * N * N,
                                     K * R * (Jj * N * N + Jz), K * Ke * Km * N * N, 0.0};
  ASSERT_EQ(g.denominator.coefficients.size(), expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) {
    EXPECT_NEAR(g.denominator.coefficients[i], expected[i],
                1e-9 * std::abs(expected[0]) + 1e-9 * std::abs(expected[i]))
        << "s^" << 4 - i;
  }
}

TEST(Seed003TransferFunction, DampedMatchesNumericalSolveOfTheEquations) {
  const auto k = seed003_constants(0.16, 0.003, 0.005);
  const auto g = wa::dc_motor_output_angle_transfer(k);
  EXPECT_EQ(g.denominator.coefficients.size(), 5u);
  EXPECT_EQ(g.denominator.coefficients.back(), 0.0);  // free rotation: a pole at s = 0
  for (double f : {1.0, 50.0, 400.0, 909.0, 3000.0}) {
    const cd s(0, 2 * std::numbers::pi * f);
    // J_j s^2 th_j + C_j s th_j = (Km/R)(U - Ke s th_j) - (G/N)(th_j/N - th_z), G = K + c s
    // J_z s^2 th_z + C_z s th_z = G (th_j/N - th_z), U = 1.
    const cd gm = k.stiffness + k.mesh_damping * s;
    Eigen::Matrix2cd a;
    a << k.inertia_motor * s * s +
             (k.damping_motor + k.torque_constant * k.back_emf_constant / k.resistance) * s +
             gm / (k.ratio * k.ratio),
        -gm / k.ratio, -gm / k.ratio, k.inertia_load * s * s + k.damping_load * s + gm;
    Eigen::Vector2cd rhs(k.torque_constant / k.resistance, 0);
    const Eigen::Vector2cd th = a.partialPivLu().solve(rhs);
    EXPECT_NEAR(std::abs(g(s) - th(1)), 0, 1e-9 * std::abs(th(1))) << f << " Hz";
  }
}

TEST(MeanStiffness, TangentOfEachLawAtTheOperatingTorque) {
  wm::StiffnessParams st;
  st.law = wm::ThreeSegmentStiffness{6.7e4, 29, 1.1e5, 108, 1.2e5};
  double x = 0;
  // model.md §4: at 60 N m the catalogue curve sits on K2 with a twist of 7.15e-4 rad.
  EXPECT_DOUBLE_EQ(wa::mean_stiffness(st, 60, &x, nullptr), 1.1e5);
  EXPECT_NEAR(x, 7.15e-4, 1e-6);
  EXPECT_DOUBLE_EQ(wa::mean_stiffness(st, 10, &x, nullptr), 6.7e4);
  EXPECT_DOUBLE_EQ(wa::mean_stiffness(st, -200, &x, nullptr), 1.2e5);
  EXPECT_LT(x, 0);

  st.law = wm::CubicStiffness{1e5, 1e12};
  const double k = wa::mean_stiffness(st, 50, &x, nullptr);
  EXPECT_NEAR(1e5 * x + 1e12 * x * x * x, 50, 1e-9);
  EXPECT_NEAR(k, 1e5 + 3e12 * x * x, 1e-6);

  st.mean_stiffness = 4.2e4;
  EXPECT_DOUBLE_EQ(wa::mean_stiffness(st, 50, nullptr, nullptr), 4.2e4);
}
