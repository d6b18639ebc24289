// Linear limit of the gear model (no backlash, constant stiffness, no friction) against the
// closed forms of a damped two-inertia oscillator.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <numbers>
#include <vector>

#include "gear_test_support.hpp"

namespace wavebench::model {
namespace {

using testing::GearRun;
using testing::kArcsec;

constexpr double kN = 50, kJ1 = 1e-3, kJ2 = 0.5, kK = 2e4;

struct Root {
  double t, rate;
};

// Zero crossings of q from the samples: a cubic Hermite on each interval through (q, q') at
// both ends is accurate to h^4, far below the tolerance asserted on.
std::vector<Root> twist_zero_crossings(const GearRun& run, const StateLayout& L, double j_eq,
                                       double c) {
  auto accel = [&](double q, double r) { return -(kK * q + c * r) / j_eq; };
  std::vector<Root> roots;
  for (std::size_t i = 0; i + 1 < run.samples.size(); ++i) {
    const auto& a = run.samples[i];
    const auto& b = run.samples[i + 1];
    const double qa = a.y[L.twist], qb = b.y[L.twist];
    if (!(qa * qb < 0)) continue;
    const double ra = a.y[L.twist_rate], rb = b.y[L.twist_rate];
    const double h = b.t - a.t;
    auto hermite = [h](double s, double ya, double da, double yb, double db) {
      const double u = s / h;
      const double h00 = (1 + 2 * u) * (1 - u) * (1 - u), h10 = u * (1 - u) * (1 - u);
      const double h01 = u * u * (3 - 2 * u), h11 = u * u * (u - 1);
      return h00 * ya + h10 * h * da + h01 * yb + h11 * h * db;
    };
    double lo = 0, hi = h;
    for (int it = 0; it < 100; ++it) {
      const double mid = 0.5 * (lo + hi);
      const double v = hermite(mid, qa, ra, qb, rb);
      ((v < 0) == (qa < 0) ? lo : hi) = mid;
    }
    const double s = 0.5 * (lo + hi);
    roots.push_back({a.t + s, hermite(s, ra, accel(qa, ra), rb, accel(qb, rb))});
  }
  return roots;
}

// Least-squares line y = a + b x; returns b.
double slope(const std::vector<double>& x, const std::vector<double>& y) {
  const double n = static_cast<double>(x.size());
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    sx += x[i];
    sy += y[i];
    sxx += x[i] * x[i];
    sxy += x[i] * y[i];
  }
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

TEST(LinearLimit, FreeVibrationFrequencyAndDampingMatchClosedForm) {
  const double zeta = 0.05;
  GearParams p = testing::bare_gear(kN, kJ1, kJ2, kK);
  p.damping.damping_ratio = zeta;
  const GearModel model(p);
  const double j_eq = kN * kN * kJ1 * kJ2 / (kN * kN * kJ1 + kJ2);
  const double wn = std::sqrt(kK / j_eq);
  EXPECT_NEAR(model.equivalent_inertia(), j_eq, 1e-15 * j_eq);
  EXPECT_NEAR(model.mesh_damping(), 2 * zeta * std::sqrt(j_eq * kK), 1e-12);

  const StateLayout& L = model.layout();
  std::vector<double> y(L.size, 0.0);
  y[L.twist] = 1e-3;
  const GearRun run = testing::run_gear(model, y, 0.5, 20000, 1e-11, 1e-13);
  const auto roots = twist_zero_crossings(run, L, j_eq, model.mesh_damping());
  ASSERT_GE(roots.size(), 20u);
  std::vector<double> k, t, log_rate;
  for (std::size_t i = 0; i < roots.size(); ++i) {
    k.push_back(static_cast<double>(i));
    t.push_back(roots[i].t);
    log_rate.push_back(std::log(std::abs(roots[i].rate)));
  }
  const double wd = std::numbers::pi / slope(k, t);
  const double sigma = -slope(t, log_rate);
  const double wn_measured = std::hypot(wd, sigma);
  EXPECT_NEAR(wn_measured / wn, 1.0, 1e-6);
  EXPECT_NEAR(wd / (wn * std::sqrt(1 - zeta * zeta)), 1.0, 1e-6);
  EXPECT_NEAR(sigma / wn_measured, zeta, 1e-6);
}

TEST(LinearLimit, SteadyResponseToSinusoidalTeMatchesFrequencyResponse) {
  // Kinematic input: J2 q'' + c q' + k q = k e + c e', so q = H(w) e with
  // H = (k + i c w) / (k - J2 w^2 + i c w); the bench reads TE = -q.
  const double c = 20, omega_in = 20, order = 7, amp = 10 * kArcsec, phase = 0.4;
  GearParams p = testing::bare_gear(kN, kJ1, kJ2, kK);
  p.damping.coefficient = c;
  p.input = KinematicInput{omega_in, 0, {}, {}};
  p.te_terms = {{"test line", TeFamily::kCustom, amp, order, 0, phase}};
  SimulationOptions o;
  o.t_end = 1.5;
  o.transient = 1.5 - 20 * 2 * std::numbers::pi / (order * omega_in);
  o.sample_rate = 20000;
  o.rtol = 1e-10;
  o.atol = 1e-12;
  const SimulationResult r = simulate(p, o);
  const double w = order * omega_in;
  const std::complex<double> i1(0, 1);
  const std::complex<double> h = (kK + i1 * c * w) / (kK - kJ2 * w * w + i1 * c * w);
  // TE = -|H| A sin(w t + phase + arg H) = Re{X e^{iwt}} with X below.
  const std::complex<double> expected = -h * amp * std::exp(i1 * (phase - std::numbers::pi / 2));
  // Least squares for a cos(wt) - b sin(wt) over whole periods (the grid makes them orthogonal).
  double sc = 0, ss = 0, cc = 0, ssq = 0;
  const auto& t = r.response.t;
  const auto& te = r.response.te;
  ASSERT_GT(t.size(), 100u);
  std::size_t n = t.size() - 1;  // drop the last sample: [transient, t_end) is whole periods
  for (std::size_t k = 0; k < n; ++k) {
    sc += te[k] * std::cos(w * t[k]);
    ss += te[k] * std::sin(w * t[k]);
    cc += std::cos(w * t[k]) * std::cos(w * t[k]);
    ssq += std::sin(w * t[k]) * std::sin(w * t[k]);
  }
  const std::complex<double> measured(sc / cc, ss / ssq);  // Re{X e^{iwt}} = Xr cos - Xi sin
  const std::complex<double> measured_x(measured.real(), -measured.imag());
  EXPECT_LT(std::abs(measured_x - expected) / std::abs(expected), 1e-4)
      << "measured " << measured_x << " expected " << expected;
}

TEST(LinearLimit, UndampedEnergyDriftBelow1e8Over1000Periods) {
  GearParams p = testing::bare_gear(kN, kJ1, kJ2, kK);
  const GearModel model(p);
  const StateLayout& L = model.layout();
  std::vector<double> y(L.size, 0.0);
  y[L.twist] = 1e-3;
  y[L.input_speed] = 0.3;  // some rigid-body motion as well
  auto energy = [&](const std::vector<double>& s) {
    const double w1 = s[L.input_speed];
    const double w2 = w1 / kN - s[L.twist_rate];
    return 0.5 * kJ1 * w1 * w1 + 0.5 * kJ2 * w2 * w2 + 0.5 * kK * s[L.twist] * s[L.twist];
  };
  const double e0 = energy(y);
  const double j_eq = kN * kN * kJ1 * kJ2 / (kN * kN * kJ1 + kJ2);
  const double period = 2 * std::numbers::pi * std::sqrt(j_eq / kK);
  const GearRun run = testing::run_gear(model, y, 1000 * period, 10, 1e-13, 1e-15);
  double worst = 0;
  for (const auto& s : run.samples) worst = std::max(worst, std::abs(energy(s.y) / e0 - 1));
  worst = std::max(worst, std::abs(energy(run.y_end) / e0 - 1));
  EXPECT_LT(worst, 1e-8);
  // Nothing dissipates: the loss account stays at zero.
  EXPECT_EQ(run.y_end[L.dissipated_energy], 0.0);
}

}  // namespace
}  // namespace wavebench::model
