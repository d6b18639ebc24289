#include "wavebench/metrology/static_te_statistics.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace wavebench::metrology {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kArcmin = kPi / 180 / 60;  // rad per arcmin

// TE over one output revolution with a known mean and two harmonics (arcmin).
double te_arcmin(double theta2, double mean) {
  return mean + 2.0 * std::sin(theta2 + 0.4) + 0.8 * std::sin(2 * theta2 - 1.1);
}

StaticTePass make_pass(Direction d, double load, double mean, const GearSense& sense) {
  StaticTePass pass;
  pass.direction = d;
  pass.load_nm = load;
  for (int k = 0; k < 24; ++k) {
    const double theta2 = 2 * kPi * k / 24 + 3.0;  // arbitrary start angle
    const double te = te_arcmin(theta2, mean) * kArcmin;
    StaticTePoint p;
    p.position = k;
    p.theta_out_rad = sense.direction_sign * theta2;
    p.theta_in_rad = sense.ratio * (theta2 - te);  // so that θ2 − θ1/N = te
    p.torque_nm = load;
    pass.points.push_back(p);
  }
  return pass;
}

TEST(GearSense, TransmissionErrorUsesTheDirectionSignOnce) {
  const GearSense sense{80, -1};
  // θ_out = −θ2 on this bench; θ1 = N·θ2 exactly gives zero TE.
  EXPECT_DOUBLE_EQ(sense.transmission_error(80 * 0.5, -0.5), 0.0);
  // The output ahead of θ1/N in the model's direction is positive TE.
  EXPECT_NEAR(sense.transmission_error(80 * 0.5, -0.5 - 1e-4), 1e-4, 1e-15);
  EXPECT_THROW((GearSense{0, 1}.validate()), std::invalid_argument);
  EXPECT_THROW((GearSense{80, 2}.validate()), std::invalid_argument);
}

TEST(StaticTe, MeanP2pPopulationStdAndEveryPoint) {
  const GearSense sense{80, -1};
  const auto s = summarise_static_pass(make_pass(Direction::kForward, 0, -1.6, sense), sense);
  ASSERT_EQ(s.points.size(), 24u);
  // 24 equally spaced points: harmonics of order < 24 average to zero exactly.
  EXPECT_NEAR(s.mean_arcmin, -1.6, 1e-9);
  EXPECT_NEAR(s.std_arcmin, std::sqrt((2.0 * 2.0 + 0.8 * 0.8) / 2), 1e-9);
  double lo = 1e9, hi = -1e9;
  for (int k = 0; k < 24; ++k) {
    const double v = te_arcmin(2 * kPi * k / 24 + 3.0, -1.6);
    lo = std::min(lo, v);
    hi = std::max(hi, v);
    EXPECT_NEAR(s.points[static_cast<std::size_t>(k)].te_arcmin, v, 1e-9);
  }
  EXPECT_NEAR(s.p2p_arcmin, hi - lo, 1e-9);
}

TEST(StaticTe, LostMotionPerPositionAndStiffnessFromTheLoadShift) {
  const GearSense sense{100, 1};
  const double stiffness = 4.2e4;                   // N·m/rad
  const double shift = 60.0 / stiffness / kArcmin;  // arcmin at 60 N·m
  const std::vector<StaticTePass> passes = {
      make_pass(Direction::kForward, 0, -1.6, sense),
      make_pass(Direction::kReverse, 0, -1.9, sense),
      make_pass(Direction::kForward, 60, -1.6 + shift, sense),
      make_pass(Direction::kReverse, 60, -1.9 + shift, sense),
  };
  const auto r = analyse_static_te(passes, sense);
  ASSERT_EQ(r.passes.size(), 4u);
  ASSERT_EQ(r.lost_motion.size(), 2u);
  for (const auto& lm : r.lost_motion) {
    ASSERT_EQ(lm.lost_motion_arcmin.size(), 24u);
    for (double v : lm.lost_motion_arcmin) EXPECT_NEAR(v, 0.3, 1e-9);
    EXPECT_NEAR(lm.mean_arcmin, 0.3, 1e-9);
  }
  ASSERT_EQ(r.load_shifts.size(), 2u);
  // Under a brake the directions part the other way (forward TE below reverse TE): the
  // lost motion is still the positive width between them.
  const std::vector<StaticTePass> braked = {
      make_pass(Direction::kForward, 60, -1.6 - 5.2, sense),
      make_pass(Direction::kReverse, 60, -1.9 + 5.2, sense),
  };
  const auto b = analyse_static_te(braked, sense);
  ASSERT_EQ(b.lost_motion.size(), 1u);
  for (double v : b.lost_motion[0].lost_motion_arcmin) EXPECT_NEAR(v, 10.1, 1e-9);
  EXPECT_NEAR(b.lost_motion[0].mean_arcmin, 10.1, 1e-9);
  EXPECT_NEAR(b.lost_motion[0].max_arcmin, 10.1, 1e-9);
  for (const auto& s : r.load_shifts) {
    EXPECT_EQ(s.load_nm, 60);
    EXPECT_NEAR(s.shift_arcmin, shift, 1e-9);
    ASSERT_TRUE(s.stiffness_nm_per_rad);
    EXPECT_NEAR(*s.stiffness_nm_per_rad, stiffness, 1e-6 * stiffness);
  }

  const auto j = to_json(r);
  ASSERT_EQ(j["static"].size(), 4u);
  const auto& first = j["static"][0];
  EXPECT_EQ(first["direction"], "forward");
  EXPECT_EQ(first["load_nm"], 0.0);
  for (const char* key : {"mean_arcmin", "p2p_arcmin", "std_arcmin"}) {
    EXPECT_TRUE(first.contains(key)) << key;
  }
  EXPECT_EQ(first["points"].size(), 24u);
  EXPECT_EQ(j["static"][3]["direction"], "reverse");
}

TEST(StaticTe, EmptyPassIsRejectedNamingIt) {
  StaticTePass pass;
  pass.direction = Direction::kReverse;
  pass.load_nm = 60;
  try {
    summarise_static_pass(pass, GearSense{80, 1});
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("reverse"), std::string::npos);
  }
}

}  // namespace
}  // namespace wavebench::metrology
