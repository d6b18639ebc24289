// The torsional loop's figures against closed forms: a three-segment gear with backlash b and a
// friction hysteresis h (the rising branch h/2 below, the falling one h/2 above the mean curve)
// has hysteresis loss b + h, backlash b, lost motion b + 2·x·T_rated/K1 (x·T_rated < T1), and
// the catalogue stiffness it was made from.
#include "wavebench/metrology/torsional_loop.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

namespace wavebench::metrology {
namespace {

constexpr double kArcmin = std::numbers::pi / 180 / 60;

ThreeSegmentStiffness unit_law() {
  ThreeSegmentStiffness s;
  s.k1 = 2.88e4;
  s.t1 = 14;
  s.k2 = 4.32e4;
  s.t2 = 48;
  s.k3 = 5.76e4;
  return s;
}

struct SyntheticGear {
  ThreeSegmentStiffness law = unit_law();
  double backlash = 0.35 * kArcmin;
  double hysteresis = 0;   // h, added to the backlash in the loop's zero-torque width
  double offset = 1.3e-3;  // the encoders' zeros: an arbitrary twist at the centre

  double twist(double torque, bool rising, int side) const {
    return offset + law.twist_at(torque) + side * backlash / 2 + (rising ? -0.5 : 0.5) * hysteresis;
  }
};

// The test's course in torque: first loading 0 → peak, unloading peak → −peak, reloading
// −peak → 0, each in `step` N·m, with `flat` points on the flat step at each zero crossing.
std::vector<LoopPoint> loop(const SyntheticGear& g, double peak = 82, double step = 0.7,
                            int flat = 4) {
  std::vector<LoopPoint> pts;
  const auto add = [&](LoopBranch b, double t, double twist) {
    pts.push_back({b, t, twist, 0, 0, false});
  };
  const auto flat_step = [&](LoopBranch b, bool rising) {
    // Across the step from one flank to the other at zero torque.
    const double from = g.twist(rising ? -1e-9 : 1e-9, rising, rising ? -1 : 1);
    const double to = g.twist(rising ? 1e-9 : -1e-9, rising, rising ? 1 : -1);
    for (int i = 1; i <= flat; ++i) add(b, 0, from + (to - from) * i / (flat + 1));
  };
  for (double t = step; t <= peak + 1e-9; t += step) {
    add(LoopBranch::kFirstLoading, t, g.twist(t, true, 1));
  }
  for (double t = peak; t > 0; t -= step) add(LoopBranch::kUnloading, t, g.twist(t, false, 1));
  flat_step(LoopBranch::kUnloading, false);
  for (double t = -step; t >= -peak - 1e-9; t -= step) {
    add(LoopBranch::kUnloading, t, g.twist(t, false, -1));
  }
  for (double t = -peak; t < 0; t += step) add(LoopBranch::kReloading, t, g.twist(t, true, -1));
  return pts;
}

LoopSensors sensors() {
  LoopSensors s;
  s.ratio = 100;
  s.output_encoder_step_rad = 2 * std::numbers::pi / 1048576;
  s.input_encoder_step_rad = 2 * std::numbers::pi / 131072;
  s.torque_step_nm = 1e-3;
  return s;
}

TorsionalLoopOptions options() {
  TorsionalLoopOptions o;
  o.rated_torque_nm = 100;
  return o;
}

double term(const UncertainFigure& f, const std::string& source) {
  for (const auto& c : f.budget) {
    if (c.source == source) return c.standard;
  }
  return -1;
}

TEST(TorsionalLoop, BacklashAloneGivesHysteresisBacklashAndLostMotionOfTheClosedForms) {
  SyntheticGear g;
  const auto r = analyse_torsional_loop(loop(g), sensors(), options());
  EXPECT_NEAR(r.hysteresis_loss_rad.value, g.backlash, 1e-12);
  EXPECT_NEAR(r.backlash_rad.value, g.backlash, 1e-12);
  EXPECT_NEAR(r.lost_motion_rad.value, g.backlash + 2 * 3 / g.law.k1, 1e-12);
  EXPECT_DOUBLE_EQ(r.lost_motion_torque_nm, 3);
  EXPECT_GT(r.lost_motion_rad.value, 0);
  // The 4 points on the step, and the two the course passes at ±0.1 N·m inside the band.
  EXPECT_EQ(r.flat_step_points, 6);
  EXPECT_EQ(r.points_voided, 0);
}

TEST(TorsionalLoop, FrictionHysteresisWidensTheLoopButNotTheFlatStep) {
  SyntheticGear g;
  g.hysteresis = 0.4 * kArcmin;
  const auto r = analyse_torsional_loop(loop(g), sensors(), options());
  EXPECT_NEAR(r.hysteresis_loss_rad.value, g.backlash + g.hysteresis, 1e-12);
  EXPECT_NEAR(r.backlash_rad.value, g.backlash, 1e-12);
  // The mid-points do not see h.
  EXPECT_NEAR(r.lost_motion_rad.value, g.backlash + 2 * 3 / g.law.k1, 1e-12);
}

TEST(TorsionalLoop, StiffnessAndBreakpointsOfTheMeanCurve) {
  SyntheticGear g;
  g.hysteresis = 0.2 * kArcmin;
  const auto r = analyse_torsional_loop(loop(g), sensors(), options());
  EXPECT_NEAR(r.k1_nm_per_rad.value, g.law.k1, 1e-3 * g.law.k1);
  EXPECT_NEAR(r.k2_nm_per_rad.value, g.law.k2, 1e-3 * g.law.k2);
  EXPECT_NEAR(r.k3_nm_per_rad.value, g.law.k3, 1e-3 * g.law.k3);
  EXPECT_NEAR(r.t1_nm.value, g.law.t1, 0.1);
  EXPECT_NEAR(r.t2_nm.value, g.law.t2, 0.2);
  // The mean curve interpolates the other branch linearly across the kinks: a few
  // thousandths of an arcsec.
  EXPECT_LT(r.fit_rms_residual_rad, 1e-7);
  ASSERT_FALSE(r.mean_torque_nm.empty());
  EXPECT_EQ(r.mean_torque_nm.size(), r.mean_twist_rad.size());
}

TEST(TorsionalLoop, TheEncoderTermIsQOverRootTwelvePerReadingOfTheWidth) {
  SyntheticGear g;
  const auto s = sensors();
  const auto r = analyse_torsional_loop(loop(g), s, options());
  const double q_out = s.output_encoder_step_rad / std::sqrt(12.0);
  const double q_in = s.input_encoder_step_rad / s.ratio / std::sqrt(12.0);
  // Hysteresis loss: two readings (±1); backlash and lost motion: four readings (±1/2).
  EXPECT_NEAR(term(r.hysteresis_loss_rad, "output encoder quantisation"), std::sqrt(2.0) * q_out,
              1e-15);
  EXPECT_NEAR(term(r.hysteresis_loss_rad, "input encoder quantisation"), std::sqrt(2.0) * q_in,
              1e-15);
  EXPECT_NEAR(term(r.lost_motion_rad, "output encoder quantisation"), q_out, 1e-15);
  EXPECT_NEAR(term(r.backlash_rad, "output encoder quantisation"), q_out, 1e-15);
  // Noise-free points: nothing left after averaging, and no input-order TE terms given.
  EXPECT_EQ(term(r.hysteresis_loss_rad, "noise after averaging"), 0);
  EXPECT_EQ(term(r.hysteresis_loss_rad, "kinematic TE while the input turns"), -1);
  EXPECT_NEAR(r.hysteresis_loss_rad.expanded(),
              2 * std::sqrt(2 * q_out * q_out + 2 * q_in * q_in +
                            std::pow(term(r.hysteresis_loss_rad, "torque sensor quantisation"), 2)),
              1e-15);
  // K1 from a twist span over T1: two readings of each encoder over T1.
  const double k1 = r.k1_nm_per_rad.value;
  EXPECT_NEAR(term(r.k1_nm_per_rad, "output encoder quantisation"),
              k1 * k1 * std::sqrt(2.0) * q_out / r.t1_nm.value, 1e-9 * k1);
}

TEST(TorsionalLoop, AnInputOrderTeTermIsBudgetedAsItsSlopeOverTheSegment) {
  SyntheticGear g;
  auto s = sensors();
  const double a = 0.2 * kArcmin;
  s.input_terms.push_back({a, 2});
  const auto r = analyse_torsional_loop(loop(g), s, options());
  // Over K1's segment the input turns N·T1/K1 = 0.049 rad: the term's change is its slope
  // 2·A times that, a relative compliance error of 2·A·N, rectangular.
  const double k1 = r.k1_nm_per_rad.value;
  EXPECT_NEAR(term(r.k1_nm_per_rad, "kinematic TE while the input turns"),
              k1 * 2 * a * s.ratio / std::sqrt(3.0), 1e-6 * k1);
  // Over the hysteresis width the input turns N·b.
  EXPECT_NEAR(term(r.hysteresis_loss_rad, "kinematic TE while the input turns"),
              2 * a * s.ratio * r.hysteresis_loss_rad.value / std::sqrt(3.0), 1e-12);
}

TEST(TorsionalLoop, NoisyPointsGiveAnUncertaintyThatCoversTheTruth) {
  SyntheticGear g;
  const double sigma = 0.1 / 60 * kArcmin;  // 0.1 arcsec left after averaging each point
  int covered = 0;
  for (unsigned seed = 1; seed <= 20; ++seed) {
    std::mt19937 rng(seed);
    std::normal_distribution<double> noise(0, sigma);
    auto pts = loop(g);
    for (auto& p : pts) {
      p.twist_rad += noise(rng);
      p.twist_standard_rad = sigma;
    }
    const auto r = analyse_torsional_loop(pts, LoopSensors{}, options());
    EXPECT_GT(term(r.lost_motion_rad, "noise after averaging"), 0);
    covered += std::abs(r.lost_motion_rad.value - (g.backlash + 2 * 3 / g.law.k1)) <=
               r.lost_motion_rad.expanded();
  }
  EXPECT_GE(covered, 17);
}

TEST(TorsionalLoop, VoidedPointsAreLeftOutAndCounted) {
  SyntheticGear g;
  auto pts = loop(g);
  pts[10].voided = true;
  pts[10].twist_rad += 1e-3;  // a slipped point far off the curve
  const auto r = analyse_torsional_loop(pts, sensors(), options());
  EXPECT_EQ(r.points_voided, 1);
  EXPECT_NEAR(r.k1_nm_per_rad.value, g.law.k1, 1e-3 * g.law.k1);
}

TEST(TorsionalLoop, ABranchWithoutPointsOnASideIsRefusedNamingIt) {
  SyntheticGear g;
  auto pts = loop(g);
  std::erase_if(pts, [](const LoopPoint& p) { return p.branch == LoopBranch::kReloading; });
  try {
    analyse_torsional_loop(pts, sensors(), options());
    FAIL() << "accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("rising branch at negative torque"), std::string::npos)
        << e.what();
  }
  auto o = options();
  o.rated_torque_nm = 0;
  EXPECT_THROW(analyse_torsional_loop(loop(g), sensors(), o), std::invalid_argument);
}

TEST(TorsionalLoop, JsonCarriesEachFigureWithItsBudgetInArcmin) {
  SyntheticGear g;
  const auto j = to_json(analyse_torsional_loop(loop(g), sensors(), options()));
  EXPECT_NEAR(j["hysteresis_loss_arcmin"]["value"].get<double>(), 0.35, 1e-9);
  EXPECT_EQ(j["hysteresis_loss_arcmin"]["k"].get<double>(), 2);
  EXPECT_TRUE(j["hysteresis_loss_arcmin"]["budget"].is_array());
  EXPECT_NEAR(j["stiffness"]["k1_nm_per_rad"]["value"].get<double>(), 2.88e4, 30);
  EXPECT_GT(j["lost_motion_arcmin"]["expanded"].get<double>(), 0);
}

}  // namespace
}  // namespace wavebench::metrology
