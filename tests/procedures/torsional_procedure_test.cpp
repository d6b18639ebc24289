// The torsional procedure on the plant bench (no CAN) against the unit's own parameters, how
// it picks its torques, and how it stops when the output moves.
#include "wavebench/procedures/torsional_procedure.hpp"

#include <gtest/gtest.h>

#include "../support/simulated_devices_gear.hpp"
#include "gear_truth.hpp"
#include "plant_bench.hpp"
#include "wavebench/simdevices/bench_plant.hpp"

namespace wavebench::procedures {
namespace {

TEST(TorsionalProcedure, LoopOnThePlantBenchGivesTheUnitsStiffnessAndBacklash) {
  const auto gear = wavebench::testing::simulated_devices_gear();
  testing::PlantBench bench(gear);  // rated 80 N·m, brake limit 100 N·m
  bench.connect();
  TorsionalOptions o;
  o.twist_step_rad = 4e-5;  // coarser than the default: a quicker unit test
  const auto out = TorsionalProcedure(o).run(bench);
  bench.wait_for(0.01);
  EXPECT_EQ(bench.brake_setting(), 0);         // released at the end, the gear unloaded
  EXPECT_DOUBLE_EQ(out.torques.t_max_nm, 80);  // rated fits under 95 N·m / 1.1
  EXPECT_EQ(out.slipped_points, 0);
  const auto& law = std::get<model::ThreeSegmentStiffness>(gear.stiffness.law);
  const auto& r = out.result;
  const double arcmin = testing::kArcminPerRadTruth;
  std::printf(
      "hysteresis %.4f (%.4f) lost motion %.4f (%.4f) arcmin; K1 %.4g K2 %.4g K3 %.4g "
      "T1 %.3g T2 %.3g\n",
      r.hysteresis_loss_rad.value * arcmin, gear.backlash.total_rad * arcmin,
      r.lost_motion_rad.value * arcmin, (gear.backlash.total_rad + 2 * 2.4 / law.k1) * arcmin,
      r.k1_nm_per_rad.value, r.k2_nm_per_rad.value, r.k3_nm_per_rad.value, r.t1_nm.value,
      r.t2_nm.value);
  // This gear carries a tooth-mesh TE term (0.03 arcmin at 404 per input turn) that ripples
  // the twist as the input turns: a tenth of an arcmin here, 0.05 on the simulated bench's unit
  // (tests/procedures/torsional_acceptance_test.cpp).
  EXPECT_NEAR(r.hysteresis_loss_rad.value * arcmin, gear.backlash.total_rad * arcmin, 0.1);
  EXPECT_NEAR(r.lost_motion_rad.value * arcmin,
              (gear.backlash.total_rad + 2 * 0.03 * 80 / law.k1) * arcmin, 0.1);
  EXPECT_NEAR(r.k1_nm_per_rad.value, law.k1, 0.05 * law.k1);
  EXPECT_NEAR(r.k2_nm_per_rad.value, law.k2, 0.05 * law.k2);
  EXPECT_NEAR(r.k3_nm_per_rad.value, law.k3, 0.05 * law.k3);
  // The branches in order: first loading, unloading, reloading; ends near zero torque.
  ASSERT_FALSE(out.points.empty());
  EXPECT_EQ(out.points.front().loop.branch, metrology::LoopBranch::kFirstLoading);
  EXPECT_EQ(out.points.back().loop.branch, metrology::LoopBranch::kReloading);
  EXPECT_LT(std::abs(out.points.back().loop.torque_nm), 1.0);
}

TEST(TorsionalProcedure, AnOutputThatMovesIsSlipAndAbortsWithTheReason) {
  testing::PlantBench bench(wavebench::testing::simulated_devices_gear());
  bench.connect();
  TorsionalOptions o;
  o.slip_threshold_rad = 1e-9;  // below the encoder's noise: every point "slips"
  o.max_slipped_points = 0;
  try {
    TorsionalProcedure(o).run(bench);
    FAIL() << "ran through";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("slipped"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("hold_torque_nm"), std::string::npos) << e.what();
  }
}

TEST(TorsionalProcedure, TorquesFitUnderTheBrakeAndSayWhy) {
  bench::BenchDescription d;
  d.sense = {100, 1};
  d.rated_torque_nm = 100;
  d.max_brake_torque_nm = 100;
  d.limits.max_brake_torque_nm = 95;
  const auto t = TorsionalProcedure(TorsionalOptions{}).torques(d);
  EXPECT_DOUBLE_EQ(t.hold_nm, 0.95 * 95);
  EXPECT_DOUBLE_EQ(t.t_max_nm, 0.95 * 95 / 1.1);
  EXPECT_NE(t.t_max_reason.find("rated torque 100"), std::string::npos) << t.t_max_reason;
  EXPECT_NE(t.t_max_reason.find("reduced"), std::string::npos) << t.t_max_reason;

  TorsionalOptions given;
  given.t_max_nm = 40;
  const auto g = TorsionalProcedure(given).torques(d);
  EXPECT_DOUBLE_EQ(g.t_max_nm, 40);
  EXPECT_EQ(g.t_max_reason.find("reduced"), std::string::npos) << g.t_max_reason;

  // A hold torque above the brake limit is refused, and so is a plan without any torque.
  TorsionalOptions over;
  over.hold_torque_nm = 120;
  EXPECT_THROW(TorsionalProcedure(over).torques(d), std::invalid_argument);
  bench::BenchDescription unrated = d;
  unrated.rated_torque_nm = 0;
  EXPECT_FALSE(TorsionalProcedure(TorsionalOptions{}).plan(unrated).refusal.empty());
  const auto plan = TorsionalProcedure(TorsionalOptions{}).plan(d);
  EXPECT_TRUE(plan.refusal.empty()) << plan.refusal;
  ASSERT_EQ(plan.brake_torques_nm.size(), 1u);
  EXPECT_EQ(plan.brake_torques_nm[0].key, "torsional.hold_torque_nm");
  EXPECT_GT(plan.bench_time_s, 0);
}

TEST(TorsionalOptions, RefuseUnknownKeysAndBadValuesNamingThem) {
  EXPECT_THROW(TorsionalOptions::from_json({{"step", 1}}), std::invalid_argument);
  try {
    TorsionalOptions::from_json({{"twist_step_rad", 0}});
    FAIL() << "accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("torsional.twist_step_rad"), std::string::npos)
        << e.what();
  }
  EXPECT_EQ(TorsionalOptions::from_json({{"window_s", 0.2}}).window_s, 0.2);
}

}  // namespace
}  // namespace wavebench::procedures
