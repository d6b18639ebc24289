// Lost motion and stiffness on the plant bench against the unit's own parameters.
#include "wavebench/procedures/lost_motion_procedure.hpp"

#include <gtest/gtest.h>

#include "../support/simulated_devices_gear.hpp"
#include "gear_truth.hpp"
#include "plant_bench.hpp"
#include "wavebench/simdevices/bench_plant.hpp"

namespace wavebench::procedures {
namespace {

TEST(LostMotionProcedure, LostMotionAndStiffnessMatchTheUnitsTruth) {
  const auto gear = wavebench::testing::simulated_devices_gear();
  testing::PlantBench bench(gear);
  bench.connect();
  LostMotionOptions o;
  const auto out = LostMotionProcedure(o).run(bench);
  ASSERT_EQ(out.record.size(), 2 * out.ladder_nm.size());
  ASSERT_EQ(out.ladder_nm.size(), 10u);  // rated 80, brake 100: the whole default ladder

  // While slipping, the gear carries the brake's torque plus the output's drag and viscous
  // losses (both between the gear and the torque sensor).
  const double n = bench.description().sense.ratio;
  const double losses =
      gear.load.output_drag_coulomb + gear.viscous_output * o.input_speed_rad_s / n;
  const double t = out.result.lost_motion_torque_nm;
  EXPECT_DOUBLE_EQ(t, 0.03 * 80);
  const double truth = gear.backlash.total_rad + 2 * testing::true_twist(gear, t + losses);
  const double arcmin = testing::kArcminPerRadTruth;
  std::printf("lost motion %.4f arcmin (truth %.4f), backlash %.4f (%.4f)\n",
              out.result.lost_motion_rad * arcmin, truth * arcmin, out.result.backlash_rad * arcmin,
              gear.backlash.total_rad * arcmin);
  EXPECT_NEAR(out.result.lost_motion_rad * arcmin, truth * arcmin, 0.2);

  const auto& law = std::get<model::ThreeSegmentStiffness>(gear.stiffness.law);
  const auto& k = out.result.stiffness;
  std::printf("K1 %.4g (%.4g) K2 %.4g (%.4g) K3 %.4g (%.4g) T1 %.3g T2 %.3g\n", k.k1, law.k1, k.k2,
              law.k2, k.k3, law.k3, k.t1, k.t2);
  EXPECT_NEAR(k.k1, law.k1, 0.05 * law.k1);
  EXPECT_NEAR(k.k2, law.k2, 0.05 * law.k2);
  EXPECT_NEAR(k.k3, law.k3, 0.05 * law.k3);
  EXPECT_GT(out.result.hysteresis_loss_j, 0);
  const auto j = out.to_json();
  EXPECT_TRUE(j.contains("stiffness"));
  EXPECT_EQ(j["points"].size(), out.record.size());
}

TEST(LostMotionOptions, RefuseAZeroTorqueAndUnknownKeys) {
  EXPECT_THROW(LostMotionOptions::from_json({{"torques_nm", {0, 5, 10, 20}}}),
               std::invalid_argument);
  EXPECT_THROW(LostMotionOptions::from_json({{"speed", 3}}), std::invalid_argument);
  EXPECT_THROW(LostMotionOptions::from_json({{"torques_nm", {5, 10}}}), std::invalid_argument);
  EXPECT_EQ(LostMotionOptions::from_json({{"input_speed_rad_s", 2}}).input_speed_rad_s, 2);
}

}  // namespace
}  // namespace wavebench::procedures
