// Issue #23 item 3 acceptance on the in-process simulated bench (CANopen on a virtual bus, the
// brake over Modbus TCP, simulated clock): a unit with memory in its mesh (hysteretic_branches,
// the unloading branch twice as stiff as the loading one) and friction at its output bearing
// (configs/twin/simulated-memory-unit.yaml) runs a static and a torsional test, and the
// torsional loop shows the hysteresis the case defines. Closed form: with constant branch
// stiffnesses K_l (loading) and K_u (unloading) and no backlash, a loop between +T and -T
// unloads from a tip along K_u to zero torque and loads on along K_l, so its zero-torque width
// is T (1/K_l - 1/K_u); equal branches (the plant before it took the model's laws) give 0.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>

#include "gear_truth.hpp"
#include "wavebench/bench/bench_config.hpp"
#include "wavebench/bench/bench_factory.hpp"
#include "wavebench/runs/static_te_procedure.hpp"
#include "wavebench/runs/torsional_procedure.hpp"

namespace wavebench::runs {
namespace {

using testing::kArcminPerRadTruth;
constexpr double kArcsecPerRad = 648000.0 / 3.141592653589793238462643;

struct MemoryUnitSim {
  MemoryUnitSim() {
    auto config = bench::default_simulated_bench_config();
    config.simulated->true_gear_case =
        std::filesystem::path(WAVEBENCH_SOURCE_DIR) / "configs/twin/simulated-memory-unit.yaml";
    bench = bench::make_simulated_bench(config);
    access = bench::simulated_access(*bench);
    bench->connect();
  }
  ~MemoryUnitSim() { bench->disconnect(); }
  std::unique_ptr<bench::Bench> bench;
  bench::SimulatedBenchAccess* access = nullptr;
};

TEST(MemoryUnitAcceptance, TheCaseReachesThePlantWithItsMemoryAndOutputFriction) {
  MemoryUnitSim sim;
  ASSERT_NE(sim.access, nullptr);
  const auto& gear = sim.access->true_gear();
  ASSERT_TRUE(std::holds_alternative<model::HystereticBranchStiffness>(gear.stiffness.law));
  EXPECT_EQ(gear.friction_side, model::FrictionSide::kOutput);
  ASSERT_TRUE(std::holds_alternative<model::CoulombStribeckFriction>(gear.friction));
}

TEST(MemoryUnitAcceptance, TorsionalLoopWidthIsTheBranchStiffnessesClosedForm) {
  MemoryUnitSim sim;
  const auto gear = sim.access->true_gear();
  const auto& law = std::get<model::HystereticBranchStiffness>(gear.stiffness.law);
  ASSERT_EQ(law.a_load, 0);
  ASSERT_EQ(law.b_load, 0);
  ASSERT_EQ(law.a_unload, 0);
  ASSERT_EQ(law.b_unload, 0);
  ASSERT_EQ(gear.backlash.total_rad, 0);
  const double k_load = law.c_load * kArcsecPerRad;
  const double k_unload = law.c_unload * kArcsecPerRad;

  const auto out = TorsionalProcedure(TorsionalOptions{}).run(*sim.bench);
  EXPECT_EQ(out.slipped_points, 0);
  const auto& r = out.result;
  const double t = 0.5 * (r.peak_torque_nm - r.valley_torque_nm);
  const double width = t * (1 / k_load - 1 / k_unload);
  const double arcmin = kArcminPerRadTruth;
  std::printf(
      "memory unit: loop +%.2f/%.2f N·m; hysteresis loss %.4f arcmin (closed form %.4f); lost "
      "motion %.4f arcmin; K1 %.4g K2 %.4g K3 %.4g N·m/rad (K_load %.4g, K_unload %.4g)\n",
      r.peak_torque_nm, r.valley_torque_nm, r.hysteresis_loss_rad.value * arcmin, width * arcmin,
      r.lost_motion_rad.value * arcmin, r.k1_nm_per_rad.value, r.k2_nm_per_rad.value,
      r.k3_nm_per_rad.value, k_load, k_unload);
  EXPECT_GT(width * arcmin, 3.0);  // a loop the encoders resolve many times over
  EXPECT_NEAR(r.hysteresis_loss_rad.value, width, 0.03 * width);
}

TEST(MemoryUnitAcceptance, StaticTeRunsAndFollowsTheLoadingBranchUnderLoad) {
  MemoryUnitSim sim;
  const auto gear = sim.access->true_gear();
  const auto& law = std::get<model::HystereticBranchStiffness>(gear.stiffness.law);
  const double k_load = law.c_load * kArcsecPerRad;
  const auto out = StaticTeProcedure(StaticTeOptions{}).run(*sim.bench);  // 24 positions, 0, 60
  ASSERT_EQ(out.passes.size(), 4u);
  EXPECT_EQ(out.settle_timeouts, 0);
  const auto& sense = sim.bench->description().sense;
  double no_load_mean[2] = {0, 0};
  double loaded_mean[2] = {0, 0};
  for (std::size_t i = 0; i < out.passes.size(); ++i) {
    const auto& pass = out.passes[i];
    const auto& summary = out.result.passes[i];
    const int d = pass.direction == procedures::Direction::kForward ? 0 : 1;
    std::vector<double> excitation;
    for (const auto& p : pass.points) {
      excitation.push_back(-testing::true_excitation(gear, p.theta_in_rad,
                                                     sense.model_output_angle(p.theta_out_rad)) *
                           kArcminPerRadTruth);
    }
    const auto e = testing::stats(excitation);
    std::printf("%s %4.0f N·m: mean %+.3f p2p %.3f (TE excitation p2p %.3f)\n",
                procedures::direction_name(pass.direction), pass.load_nm, summary.mean_arcmin,
                summary.p2p_arcmin, e.p2p);
    // The twist under the pass's steady torque is near constant: the TE's shape is the
    // excitation's.
    EXPECT_NEAR(summary.p2p_arcmin, e.p2p, 0.25);
    (pass.load_nm > 0 ? loaded_mean : no_load_mean)[d] = summary.mean_arcmin;
  }
  // Under the brake's 60 N·m the mesh loads along its loading branch: the mean TE moves by
  // about 60 / K_load against the direction of travel.
  const double shift = 60 / k_load * kArcminPerRadTruth;
  for (int d = 0; d < 2; ++d) {
    const double measured = std::abs(loaded_mean[d] - no_load_mean[d]);
    std::printf("%s: mean shift under 60 N·m %.3f arcmin (60/K_load %.3f)\n",
                d == 0 ? "forward" : "reverse", measured, shift);
    EXPECT_NEAR(measured, shift, 0.15 * shift);
  }
}

}  // namespace
}  // namespace wavebench::runs
