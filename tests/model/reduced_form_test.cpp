// Seed 001 writes the gear as one twist coordinate:
//   J_dl q'' + C (q' - e') + K f(q - e) = J_dl [T_m/(N J1) + T_L/J2],
// J_dl = N^2 J1 J2 / (N^2 J1 + J2) (here in model.md's signs, q = theta1/N - theta2). With the
// rigid-body coordinate P = N J1 theta1 + J2 theta2 (P'' = N T_m - T_L) it gives theta1 for the
// angle-dependent TE. Written here from scratch, it must give the two-inertia model's twist.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "gear_test_support.hpp"

namespace wavebench::model {
namespace {

using testing::kArcsec;

constexpr double kN = 80, kJ1 = 3e-4, kJ2 = 0.3, kK = 5e4;

class SeedOneCoordinate final : public solver::OdeSystem {
 public:
  SeedOneCoordinate(const GearParams& p, double c, double b) : p_(p), c_(c), half_(b / 2) {}
  std::size_t continuous_size() const override { return 4; }  // q, q', P, P'
  void derivatives(double t, std::span<const double> y, std::span<const double>,
                   std::span<double> f) const override {
    const double m = kN * kJ1 + kJ2 / kN;
    const double theta1 = (y[2] + kJ2 * y[0]) / m;
    const double omega1 = (y[3] + kJ2 * y[1]) / m;
    double e = 0, de = 0;
    for (const auto& term : p_.te_terms) {
      const double arg = term.order_input * theta1 + term.phase_rad;
      e += term.amplitude_rad * std::sin(arg);
      de += term.amplitude_rad * term.order_input * omega1 * std::cos(arg);
    }
    const double delta = y[0] - e;
    const double fd = delta > half_ ? delta - half_ : (delta < -half_ ? delta + half_ : 0.0);
    auto sine = [t](const Sinusoid& s) {
      return s.offset +
             s.amplitude * std::sin(2 * std::numbers::pi * s.frequency_hz * t + s.phase_rad);
    };
    const double tm = sine(std::get<TorqueInput>(p_.input).torque) + sine(p_.load.drive_ripple);
    const double tl = sine(p_.load.output_torque);
    const double jdl = kN * kN * kJ1 * kJ2 / (kN * kN * kJ1 + kJ2);
    f[0] = y[1];
    f[1] = (jdl * (tm / (kN * kJ1) + tl / kJ2) - c_ * (y[1] - de) - kK * fd) / jdl;
    f[2] = y[3];
    f[3] = kN * tm - tl;
  }
  std::size_t witness_count() const override { return half_ > 0 ? 2 : 0; }
  void witnesses(double t, std::span<const double> y, std::span<const double> d,
                 std::span<double> g) const override {
    // Same kinks as the model locates: Delta = +-b/2 (Delta from a derivative call's parts).
    const double m = kN * kJ1 + kJ2 / kN;
    const double theta1 = (y[2] + kJ2 * y[0]) / m;
    double e = 0;
    for (const auto& term : p_.te_terms) {
      e += term.amplitude_rad * std::sin(term.order_input * theta1 + term.phase_rad);
    }
    (void)t;
    (void)d;
    g[0] = y[0] - e - half_;
    g[1] = y[0] - e + half_;
  }

 private:
  GearParams p_;
  double c_, half_;
};

std::size_t compare(const GearParams& p, double t_end) {
  const GearModel model(p);
  const StateLayout& L = model.layout();
  const double w0 = p.nominal_input_speed;
  std::vector<double> y(L.size, 0.0);
  y[L.twist] = 1.2 * p.backlash.total_rad / 2 + 2e-4;
  const testing::GearRun two = testing::run_gear(model, y, t_end, 5000, 1e-11, 1e-13);

  const SeedOneCoordinate reduced(p, model.mesh_damping(), p.backlash.total_rad);
  std::vector<double> z = {y[L.twist], 0.0, kJ2 * (0.0 - y[L.twist]),
                           kN * kJ1 * w0 + kJ2 * w0 / kN};
  auto integrator =
      solver::make_integrator(solver::IntegratorKind::kDormandPrince45, {1e-11, 1e-13}, 1e-5, 0);
  solver::TrajectoryOptions opt;
  opt.t_end = t_end;
  opt.sample_rate = 5000;
  solver::TrajectoryRunner runner(*integrator, reduced, opt);
  std::vector<double> q_reduced;
  runner.on_sample([&](double, std::span<const double> s, std::span<const double>) {
    q_reduced.push_back(s[0]);
  });
  std::vector<double> d;
  runner.run(0.0, z, d);

  EXPECT_EQ(q_reduced.size(), two.samples.size());
  if (q_reduced.size() != two.samples.size()) return 0;
  double worst = 0, size = 0;
  for (std::size_t i = 0; i < q_reduced.size(); ++i) {
    worst = std::max(worst, std::abs(q_reduced[i] - two.samples[i].y[L.twist]));
    size = std::max(size, std::abs(q_reduced[i]));
  }
  EXPECT_LT(worst, 1e-7 * size) << "largest twist " << size;
  EXPECT_GT(size, 1e-4);
  return two.result.events.size();
}

GearParams seed_case() {
  GearParams p = testing::bare_gear(kN, kJ1, kJ2, kK);
  p.nominal_input_speed = 50;
  p.te_terms = {{"T1l_1", TeFamily::kWaveGenerator, 5 * kArcsec, 1, 0, 0.2},
                {"dS_fix", TeFamily::kHousing, 10 * kArcsec, 2, 0, 1.0},
                {"df_i1", TeFamily::kToothMesh, 1 * kArcsec, 2 * 162, 0, -0.5}};
  p.input = TorqueInput{{0.5, 0.1, 30, 0}};
  p.load.drive_ripple = {0.05, 0.02, 70, 0.3};
  p.load.output_torque = {20, 5, 12, 0.1};
  return p;
}

TEST(SeedReducedForm, MatchesTwoInertiaTwistWithDampingNoBacklash) {
  GearParams p = seed_case();
  p.damping.damping_ratio = 0.06;
  compare(p, 0.3);
}

TEST(SeedReducedForm, MatchesTwoInertiaTwistWithBacklash) {
  GearParams p = seed_case();
  p.backlash.total_rad = 60 * kArcsec;
  p.load.output_torque = {2, 8, 12, 0.1};  // the load reverses: flank changes
  EXPECT_GE(compare(p, 0.2), 2u);          // contact lost and made again
}

}  // namespace
}  // namespace wavebench::model
