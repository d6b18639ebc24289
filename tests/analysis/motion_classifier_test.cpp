// Poincare sections and the motion class on synthetic motions with known answers: periodic,
// period-2, quasi-periodic (two incommensurate tones), chaotic (logistic map, Duffing).
#include "wavebench/analysis/motion_classifier.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "wavebench/analysis/poincare_section.hpp"

namespace wa = wavebench::analysis;

namespace {

constexpr double kPi = std::numbers::pi;

struct Trajectory {
  std::vector<double> t, phase, x, v;
  std::vector<wa::PhasePoint> portrait() const {
    std::vector<wa::PhasePoint> p;
    for (std::size_t i = 0; i < t.size(); ++i) p.push_back({x[i], v[i]});
    return p;
  }
};

// x(t) sampled finely; phase = omega t strobes once per excitation period 2 pi / omega.
template <class F, class G>
Trajectory sample(F x, G v, double omega, double periods, int per_period) {
  Trajectory tr;
  const double dt = 2 * kPi / omega / per_period;
  const auto n = static_cast<std::size_t>(periods * per_period);
  for (std::size_t i = 0; i <= n; ++i) {
    const double t = static_cast<double>(i) * dt;
    tr.t.push_back(t);
    tr.phase.push_back(omega * t + 0.1);
    tr.x.push_back(x(t));
    tr.v.push_back(v(t));
  }
  return tr;
}

wa::MotionClassification classify(const Trajectory& tr) {
  const auto section = wa::strobe_on_phase(tr.t, tr.phase, tr.x, tr.v);
  const auto portrait = tr.portrait();
  return wa::classify_motion(section.points, portrait, {});
}

// Duffing x'' + d x' - x + x^3 = g cos(w t), RK4 with 200 steps per forcing period.
Trajectory duffing(double d, double g, double w, int periods) {
  Trajectory tr;
  const int per = 200;
  const double h = 2 * kPi / w / per;
  double x = 1, v = 0, t = 0;
  auto acc = [&](double tt, double xx, double vv) {
    return -d * vv + xx - xx * xx * xx + g * std::cos(w * tt);
  };
  for (int i = 0; i < periods * per; ++i) {
    if (i >= 100 * per) {  // transient dropped
      tr.t.push_back(t);
      tr.phase.push_back(w * t);
      tr.x.push_back(x);
      tr.v.push_back(v);
    }
    const double k1x = v, k1v = acc(t, x, v);
    const double k2x = v + 0.5 * h * k1v, k2v = acc(t + 0.5 * h, x + 0.5 * h * k1x, k2x);
    const double k3x = v + 0.5 * h * k2v, k3v = acc(t + 0.5 * h, x + 0.5 * h * k2x, k3x);
    const double k4x = v + h * k3v, k4v = acc(t + h, x + h * k3x, k4x);
    x += h / 6 * (k1x + 2 * k2x + 2 * k3x + k4x);
    v += h / 6 * (k1v + 2 * k2v + 2 * k3v + k4v);
    // Recomputing t from the index keeps the strobe phase free of round-off drift.
    t = (i + 1) * h;
  }
  return tr;
}

}  // namespace

TEST(PoincareSection, StrobesAtEveryTurnOfThePhase) {
  const std::vector<double> t{0, 1, 2, 3, 4};
  const std::vector<double> phase{0.5 * kPi, 1.5 * kPi, 2.5 * kPi, 6.5 * kPi, 7 * kPi};
  const std::vector<double> x{0, 1, 2, 3, 4};
  const auto s = wa::strobe_on_phase(t, phase, x, x);
  ASSERT_EQ(s.t.size(), 3u);  // 2 pi at t = 1.5, 4 pi at t = 2.375, 6 pi at t = 2.875
  EXPECT_NEAR(s.t[0], 1.5, 1e-12);
  EXPECT_NEAR(s.t[1], 2.375, 1e-12);
  EXPECT_NEAR(s.t[2], 2.875, 1e-12);
  EXPECT_NEAR(s.points[2].x, 2.875, 1e-12);
  const std::vector<double> backwards{0, -1.5 * kPi, -2.5 * kPi, -3 * kPi, -4.5 * kPi};
  EXPECT_EQ(wa::strobe_on_phase(t, backwards, x, x).t.size(), 2u);
}

TEST(MotionClassifier, PeriodicMotionIsPeriodOne) {
  const double w = 2 * kPi * 90;
  const auto tr =
      sample([&](double t) { return 1e-5 * std::sin(w * t) + 3e-6 * std::sin(3 * w * t); },
             [&](double t) { return 1e-5 * w * std::cos(w * t) + 9e-6 * w * std::cos(3 * w * t); },
             w, 200, 100);
  const auto m = classify(tr);
  EXPECT_EQ(m.motion, wa::MotionClass::kPeriod1) << m.summary;
  EXPECT_EQ(m.evidence.clusters, 1);
  EXPECT_LT(m.evidence.spread, 1e-3);
}

TEST(MotionClassifier, SubharmonicIsPeriodTwo) {
  const double w = 2.0;
  const auto tr = sample(
      [&](double t) { return std::sin(w * t) + 0.4 * std::sin(0.5 * w * t); },
      [&](double t) { return w * std::cos(w * t) + 0.2 * w * std::cos(0.5 * w * t); }, w, 300, 100);
  const auto m = classify(tr);
  EXPECT_EQ(m.motion, wa::MotionClass::kPeriodN) << m.summary;
  EXPECT_EQ(m.evidence.period, 2);
  EXPECT_EQ(m.evidence.clusters, 2);
}

TEST(MotionClassifier, TwoIncommensurateTonesAreQuasiPeriodic) {
  const double w = 1.0, w2 = std::sqrt(2.0);
  const auto tr = sample(
      [&](double t) { return std::sin(w * t) + 0.5 * std::sin(w2 * t); },
      [&](double t) { return w * std::cos(w * t) + 0.5 * w2 * std::cos(w2 * t); }, w, 1000, 64);
  const auto m = classify(tr);
  EXPECT_EQ(m.motion, wa::MotionClass::kQuasiPeriodic) << m.summary;
  EXPECT_GT(m.evidence.clusters, 16);
  EXPECT_NEAR(m.evidence.correlation_dimension, 1.0, 0.2);
  EXPECT_LT(std::abs(m.evidence.lyapunov_per_period), 0.05);
}

TEST(MotionClassifier, LogisticMapIsChaotic) {
  // x_{n+1} = 4 x_n (1 - x_n): Lyapunov exponent ln 2 per iteration.
  std::vector<wa::PhasePoint> section;
  double x = 0.2345;
  for (int i = 0; i < 1500; ++i) {
    const double next = 4 * x * (1 - x);
    section.push_back({x, next});
    x = next;
  }
  const auto m = wa::classify_motion(section, {}, {});
  EXPECT_EQ(m.motion, wa::MotionClass::kChaotic) << m.summary;
  EXPECT_NEAR(m.evidence.lyapunov_per_period, std::log(2.0), 0.25);
}

TEST(MotionClassifier, DuffingOscillator) {
  // Ueda/Moon parameters: d = 0.3, g = 0.5, w = 1.2 is the textbook strange attractor.
  const auto chaotic = classify(duffing(0.3, 0.5, 1.2, 1100));
  EXPECT_EQ(chaotic.motion, wa::MotionClass::kChaotic) << chaotic.summary;
  EXPECT_GT(chaotic.evidence.lyapunov_per_period, 0.1);
  // Small forcing: the orbit around one well is periodic.
  const auto periodic = classify(duffing(0.3, 0.1, 1.2, 300));
  EXPECT_EQ(periodic.motion, wa::MotionClass::kPeriod1) << periodic.summary;
}

TEST(MotionClassifier, TooFewPointsIsUndetermined) {
  std::vector<wa::PhasePoint> section{{0, 0}, {1, 1}};
  EXPECT_EQ(wa::classify_motion(section, {}, {}).motion, wa::MotionClass::kUndetermined);
  EXPECT_STREQ(wa::motion_class_name(wa::MotionClass::kQuasiPeriodic), "quasi-periodic");
}

TEST(MotionClassifier, SlowlyDriftingSectionIsQuasiPeriodicNotPeriodOne) {
  // Two tones 0.3 % apart: each strobe moves the point a little along a closed curve, so
  // consecutive points share a cluster although the motion never repeats.
  const double w = 1.0, w2 = 1.003;
  const auto tr = sample(
      [&](double t) { return std::sin(w * t) + 0.5 * std::sin(w2 * t); },
      [&](double t) { return w * std::cos(w * t) + 0.5 * w2 * std::cos(w2 * t); }, w, 1000, 64);
  const auto m = classify(tr);
  EXPECT_EQ(m.motion, wa::MotionClass::kQuasiPeriodic) << m.summary;
}

TEST(MotionClassifier, CommensurateLinesRepeatingAfterManyStrobesAreQuasiPeriodic) {
  // 90 Hz and 89.333 Hz (ratio 135/134) strobed at 90 Hz: the sequence repeats after 135.
  const double f1 = 90, f2 = 90.0 * 134 / 135;
  const auto tr = sample(
      [&](double t) { return std::sin(2 * kPi * f1 * t) + 0.2 * std::sin(2 * kPi * f2 * t); },
      [&](double t) {
        return 2 * kPi * (f1 * std::cos(2 * kPi * f1 * t) + 0.2 * f2 * std::cos(2 * kPi * f2 * t));
      },
      2 * kPi * f1, 400, 200);
  const auto m = classify(tr);
  EXPECT_EQ(m.motion, wa::MotionClass::kQuasiPeriodic) << m.summary;
  EXPECT_EQ(m.evidence.period, 135);
}

TEST(MotionClassifier, ContractingTransientIsUndetermined) {
  // A section spiralling into a fixed point (factor 0.8 per strobe): exponent ln 0.8 < 0.
  std::vector<wa::PhasePoint> section;
  for (int k = 0; k < 100; ++k) {
    const double r = std::pow(0.8, k);
    section.push_back({r * std::cos(2.4 * k), r * std::sin(2.4 * k)});
  }
  const auto m = wa::classify_motion(section, {}, {});
  EXPECT_EQ(m.motion, wa::MotionClass::kUndetermined) << m.summary;
  EXPECT_LT(m.evidence.lyapunov_per_period, -0.05);
}
