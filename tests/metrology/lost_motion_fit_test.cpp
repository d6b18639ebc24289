#include "wavebench/metrology/lost_motion_fit.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace wavebench::metrology {
namespace {

constexpr double kArcmin = std::numbers::pi / 180 / 60;

// Catalogue three-segment curve (model.md §4, size 32 class).
ThreeSegmentStiffness catalogue() {
  ThreeSegmentStiffness s;
  s.t1 = 29;
  s.k1 = 6.7e4;
  s.t2 = 108;
  s.k2 = 1.1e5;
  s.k3 = 1.2e5;
  return s;
}

// Forward travel up and down the ladder, then reverse travel up and down; backlash B between
// the branches around an arbitrary offset.
std::vector<TorqueTwistPoint> ladder_record(double backlash, double offset) {
  const auto curve = catalogue();
  const std::vector<double> ladder = {2, 5, 10, 15, 20, 25, 35, 45, 60, 75, 90, 100, 115, 130, 145};
  std::vector<TorqueTwistPoint> rec;
  for (int travel : {+1, -1}) {
    const double o = offset + travel * backlash / 2;
    for (double t : ladder) rec.push_back({travel * t, o + curve.twist_at(travel * t), travel});
    for (auto it = ladder.rbegin(); it != ladder.rend(); ++it) {
      rec.push_back({travel * *it, o + curve.twist_at(travel * *it), travel});
    }
  }
  return rec;
}

TEST(ThreeSegmentStiffness, CatalogueTwistAtSixtyNewtonMetres) {
  EXPECT_NEAR(catalogue().twist_at(60), 7.15e-4, 0.01e-4);
  EXPECT_NEAR(catalogue().twist_at(60), 29 / 6.7e4 + 31 / 1.1e5, 1e-15);
  EXPECT_DOUBLE_EQ(catalogue().twist_at(-60), -catalogue().twist_at(60));
}

TEST(LostMotionFit, RecoversCatalogueStiffnessBreakpointsBacklashAndLostMotion) {
  const double backlash = 1.0 * kArcmin;
  const auto rec = ladder_record(backlash, -3e-4);
  LostMotionOptions options;
  options.rated_torque_nm = 100;
  options.lost_motion_fraction = 0.03;
  const auto r = analyse_lost_motion(rec, options);
  EXPECT_NEAR(r.stiffness.k1, 6.7e4, 0.005 * 6.7e4);
  EXPECT_NEAR(r.stiffness.k2, 1.1e5, 0.005 * 1.1e5);
  EXPECT_NEAR(r.stiffness.k3, 1.2e5, 0.005 * 1.2e5);
  EXPECT_NEAR(r.stiffness.t1, 29, 0.3);
  EXPECT_NEAR(r.stiffness.t2, 108, 1.0);
  EXPECT_NEAR(r.stiffness.twist_at(60), 7.15e-4, 0.01e-4);
  EXPECT_NEAR(r.backlash_rad, backlash, 1e-3 * backlash);
  EXPECT_NEAR(r.forward_offset_rad, -3e-4 + backlash / 2, 1e-8);
  // ±3 N·m lies on the first segment between ladder points 2 and 5: exact by interpolation.
  EXPECT_NEAR(r.lost_motion_rad, backlash + 2 * 3 / 6.7e4, 1e-12);
  EXPECT_NEAR(r.lost_motion_torque_nm, 3, 1e-12);
  // Loading and unloading retrace the same curve here: the loop encloses no area.
  EXPECT_NEAR(r.hysteresis_loss_j, 0, 1e-12);
  const auto j = to_json(r);
  EXPECT_NEAR(j["backlash_arcmin"].get<double>(), 1.0, 1e-3);
}

TEST(LostMotionFit, LoopAreaOfAKnownParallelogram) {
  // Loading branch θ = T/K, unloading branch shifted by h: area = h·(T_max − T_min) per loop.
  const double k = 1e5, h = 2e-5;
  std::vector<TorqueTwistPoint> loop;
  for (int i = 0; i <= 10; ++i) loop.push_back({10.0 * i, 10.0 * i / k, 1});
  for (int i = 10; i >= 0; --i) loop.push_back({10.0 * i, 10.0 * i / k + h, 1});
  EXPECT_NEAR(loop_area(loop), h * 100, 1e-12);
}

TEST(LostMotionFit, MissingBranchIsRejected) {
  auto rec = ladder_record(1e-4, 0);
  std::erase_if(rec, [](const TorqueTwistPoint& p) { return p.travel < 0; });
  LostMotionOptions options;
  options.rated_torque_nm = 100;
  EXPECT_THROW(analyse_lost_motion(rec, options), std::invalid_argument);
  options.rated_torque_nm = 0;
  EXPECT_THROW(options.validate(), std::invalid_argument);
}

}  // namespace
}  // namespace wavebench::metrology
