// Every config shipped in configs/twin loads, and the reference cases hold the values that
// model.md §10 and the seeds give.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numbers>
#include <variant>

#include "wavebench/config/twin_case.hpp"

namespace wavebench::config {
namespace {

namespace fs = std::filesystem;
const fs::path kTwinDir = fs::path(WAVEBENCH_SOURCE_DIR) / "configs" / "twin";
constexpr double kPi = std::numbers::pi;

TEST(ShippedConfigs, EveryTwinConfigLoads) {
  int count = 0;
  for (const auto& entry : fs::directory_iterator(kTwinDir)) {
    if (entry.path().extension() != ".yaml") continue;
    SCOPED_TRACE(entry.path().string());
    EXPECT_NO_THROW(load_twin_case(entry.path()));
    ++count;
  }
  EXPECT_GE(count, 4);
}

TEST(ShippedConfigs, Xb80HasTheSeedLinesAndAResolvingRecord) {
  const auto c = load_twin_case(kTwinDir / "xb-80-134h.yaml");
  const auto& g = c.gear.geometry;
  EXPECT_EQ(g.z_flex, 268);
  EXPECT_EQ(g.z_circ, 270);
  EXPECT_DOUBLE_EQ(g.ratio, 134.0);
  EXPECT_DOUBLE_EQ(c.gear.inertia_input, 2.2e-4);
  EXPECT_DOUBLE_EQ(c.gear.inertia_output, 0.2839);
  EXPECT_DOUBLE_EQ(c.gear.damping.damping_ratio.value(), 0.06);
  EXPECT_NEAR(c.gear.backlash.total_rad, 8.0 / 60 * kPi / 180, 1e-15);
  const double omega1 = 2680 * 2 * kPi / 60;
  EXPECT_DOUBLE_EQ(c.gear.nominal_input_speed, omega1);

  // Which lines the TE terms put where, and which of them is the largest excitation.
  double a44 = 0, a89 = 0, a90 = 0, amesh = 0;
  for (const auto& t : c.gear.te_terms) {
    const double f = model::te_term_frequency_hz(t, g, omega1);
    if (std::abs(f - 44.6667) < 0.01)
      a44 += t.amplitude_rad;
    else if (std::abs(f - 89.3333) < 0.01)
      a89 += t.amplitude_rad;
    else if (std::abs(f - 90.0) < 0.01)
      a90 += t.amplitude_rad;
    else if (std::abs(f - 24120.0) < 0.1)
      amesh += t.amplitude_rad;
    else
      ADD_FAILURE() << "unexpected line at " << f << " Hz from " << t.source;
  }
  EXPECT_GT(a90, 2 * a89);
  EXPECT_GT(a89, 5 * a44);
  EXPECT_GT(amesh, 0.0);
  // Record: Hann main lobe half-width 2/T must stay below the 0.67 Hz line spacing.
  const double record = c.solver.t_end - c.solver.transient;
  EXPECT_GE(record, 4.0);
  EXPECT_GE(c.solver.sample_rate, 60000.0);
  EXPECT_GT(c.solver.sample_rate / 2, 24120.0);
  EXPECT_GT(c.gear.load.output_drag_coulomb, 0.0);
}

TEST(ShippedConfigs, DcMotorMatchesSeed003Table1) {
  const auto c = load_twin_case(kTwinDir / "dc-motor-seed003.yaml");
  const auto& m = std::get<model::DcMotorInput>(c.gear.input);
  EXPECT_EQ(m.resistance, 6.0);
  EXPECT_EQ(m.torque_constant, 0.52);
  EXPECT_EQ(m.back_emf_constant, 0.52);
  EXPECT_EQ(m.voltage.amplitude, 24.0);
  EXPECT_EQ(m.voltage.frequency_hz, 50.0);
  EXPECT_EQ(c.gear.viscous_input, 0.003);
  EXPECT_EQ(c.gear.viscous_output, 0.005);
  EXPECT_EQ(c.gear.damping.coefficient.value(), 0.16);
  EXPECT_EQ(c.gear.geometry.ratio, 100.0);
  EXPECT_EQ(c.gear.stiffness.mean_stiffness.value(), 7.8e5);
  EXPECT_EQ(c.gear.inertia_input, 6.8e-4);
  EXPECT_EQ(c.gear.inertia_output, 2.4e-2);
  const auto& fm = std::get<model::FadingMemoryStiffness>(c.gear.stiffness.law);
  EXPECT_EQ(fm.memory_gain, 40000.0);
  EXPECT_EQ(fm.memory_decay, 300.0);
  EXPECT_EQ(fm.a, 0.12);
  EXPECT_EQ(fm.b, 0.56);
  EXPECT_EQ(fm.c, 52000.0);
  EXPECT_TRUE(std::holds_alternative<model::LuGreFriction>(c.gear.friction));
}

TEST(ShippedConfigs, HysteresisCaseSweeps100To2700Rpm) {
  const auto c = load_twin_case(kTwinDir / "hysteresis-seed001.yaml");
  EXPECT_TRUE(std::holds_alternative<model::HystereticBranchStiffness>(c.gear.stiffness.law));
  EXPECT_TRUE(c.analysis.sweep.enabled);
  EXPECT_DOUBLE_EQ(c.analysis.sweep.from_speed, 100 * 2 * kPi / 60);
  EXPECT_DOUBLE_EQ(c.analysis.sweep.to_speed, 2700 * 2 * kPi / 60);
}

TEST(ShippedConfigs, BenchUnitGivesSeed004StaticFigures) {
  const auto c = load_twin_case(kTwinDir / "bench-unit-seed004.yaml");
  // Static (kinematic) TE over one output revolution: e(theta1 = N theta2, theta2).
  const double n = c.gear.geometry.ratio;
  double lo = 1e9, hi = -1e9;
  for (int i = 0; i < 400000; ++i) {
    const double th2 = 2 * kPi * i / 400000.0;
    double e = 0;
    for (const auto& t : c.gear.te_terms) {
      e += t.amplitude_rad * std::sin(t.order_input * n * th2 + t.order_output * th2 + t.phase_rad);
    }
    lo = std::min(lo, e);
    hi = std::max(hi, e);
  }
  const double arcmin = kPi / 180 / 60;
  EXPECT_NEAR((hi - lo) / arcmin, 5.5, 0.3);
  // Twist at 60 N*m on the three-segment curve: the ~5 arcmin shift of mean TE.
  const auto& s = std::get<model::ThreeSegmentStiffness>(c.gear.stiffness.law);
  const double twist = s.t1 / s.k1 + (s.t2 - s.t1) / s.k2 + (60 - s.t2) / s.k3;
  EXPECT_NEAR(twist / arcmin, 5.0, 0.3);
}

}  // namespace
}  // namespace wavebench::config
