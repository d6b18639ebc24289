// Issue #23 item 3 acceptance on the in-process simulated bench (CANopen on a virtual bus, the
// brake over Modbus TCP, simulated clock): a unit with memory in its mesh (Bouc-Wen, form 7) and
// friction at its output bearing (configs/twin/simulated-memory-unit.yaml) runs a static and a
// torsional test, and the torsional loop shows the hysteresis the case defines: its zero-torque
// width is the law's own loop between the measured peak torques, integrated here in the twist
// alone (no time, no servo, no plant). A memoryless spring without backlash gives 0.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>

#include "gear_truth.hpp"
#include "wavebench/bench/bench_config.hpp"
#include "wavebench/bench/bench_factory.hpp"
#include "wavebench/model/bouc_wen_spring.hpp"
#include "wavebench/procedures/static_te_procedure.hpp"
#include "wavebench/procedures/torsional_procedure.hpp"

namespace wavebench::procedures {
namespace {

using testing::kArcminPerRadTruth;

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
  ASSERT_TRUE(std::holds_alternative<model::BoucWenStiffness>(gear.stiffness.law));
  EXPECT_EQ(gear.friction_side, model::FrictionSide::kOutput);
  ASSERT_TRUE(std::holds_alternative<model::CoulombStribeckFriction>(gear.friction));
}

// The zero-torque width of the law's loop along the procedure's path, integrated
// quasi-statically in the twist (no time, no servo, no plant): first loading from the virgin
// state to +T, unloading to -T, reloading to +T; the width is where the unloading branch
// crosses zero torque less where the reloading one does (Bouc-Wen's first loop is not yet its
// symmetric steady one, so the path matters).
double bouc_wen_loop_width(const model::BoucWenStiffness& p, double t_peak, double t_valley) {
  const model::BoucWenSpring law(p);
  const double dx = 1e-8;
  double x = 0, w = 0;
  double up_zero = 0, down_zero = 0;
  const double targets[] = {t_peak, -t_valley, t_peak};
  for (int leg = 0; leg < 3; ++leg) {
    const double target = targets[leg];
    const double dir = target > 0 ? 1.0 : -1.0;
    double torque = law.torque(x, w);
    for (int i = 0; i < 10000000 && torque * dir < target * dir; ++i) {
      const double before = torque;
      w += law.hysteretic_rate(dir * dx, w);
      x += dir * dx;
      torque = law.torque(x, w);
      if (before * torque <= 0 && leg >= 1) (dir > 0 ? up_zero : down_zero) = x;
    }
  }
  return std::abs(down_zero - up_zero);
}

TEST(MemoryUnitAcceptance, TorsionalLoopWidthIsTheLawsQuasiStaticLoop) {
  MemoryUnitSim sim;
  const auto gear = sim.access->true_gear();
  const auto& law = std::get<model::BoucWenStiffness>(gear.stiffness.law);
  ASSERT_EQ(gear.backlash.total_rad, 0);

  const auto out = TorsionalProcedure(TorsionalOptions{}).run(*sim.bench);
  EXPECT_EQ(out.slipped_points, 0);
  const auto& r = out.result;
  const double width = bouc_wen_loop_width(law, r.peak_torque_nm, -r.valley_torque_nm);
  const double arcmin = kArcminPerRadTruth;
  std::printf(
      "memory unit: loop +%.2f/%.2f N·m; hysteresis loss %.4f arcmin (law's loop %.4f); lost "
      "motion %.4f arcmin; K1 %.4g K2 %.4g K3 %.4g N·m/rad\n",
      r.peak_torque_nm, r.valley_torque_nm, r.hysteresis_loss_rad.value * arcmin, width * arcmin,
      r.lost_motion_rad.value * arcmin, r.k1_nm_per_rad.value, r.k2_nm_per_rad.value,
      r.k3_nm_per_rad.value);
  EXPECT_GT(width * arcmin, 1.0);  // a loop the encoders resolve many times over
  // Measured 3.46 arcmin against the quasi-static 2.86 (+21 %). Driven smoothly (torque ramps,
  // no servo) the plant's loop is the law's within 2.5 % (plant_laws_test.cpp), so the extra
  // width is the bench's motion: the servo's position loop dithers at each hold point and each
  // dither is a Bouc-Wen minor loop the quasi-static path leaves out. The test holds the
  // measured loop within [-5 %, +30 %] of the law's; equal branches would give 0.
  EXPECT_GE(r.hysteresis_loss_rad.value, 0.95 * width);
  EXPECT_LE(r.hysteresis_loss_rad.value, 1.30 * width);
}

TEST(MemoryUnitAcceptance, StaticTeRunsWithTheExcitationsShape) {
  MemoryUnitSim sim;
  const auto gear = sim.access->true_gear();
  const auto out = StaticTeProcedure(StaticTeOptions{}).run(*sim.bench);  // 24 positions, 0, 60
  ASSERT_EQ(out.passes.size(), 4u);
  EXPECT_EQ(out.settle_timeouts, 0);
  const auto& sense = sim.bench->description().sense;
  for (std::size_t i = 0; i < out.passes.size(); ++i) {
    const auto& pass = out.passes[i];
    const auto& summary = out.result.passes[i];
    std::vector<double> excitation;
    for (const auto& p : pass.points) {
      excitation.push_back(-testing::true_excitation(gear, p.theta_in_rad,
                                                     sense.model_output_angle(p.theta_out_rad)) *
                           kArcminPerRadTruth);
    }
    const auto e = testing::stats(excitation);
    std::printf("%s %4.0f N·m: mean %+.3f p2p %.3f (TE excitation p2p %.3f)\n",
                metrology::direction_name(pass.direction), pass.load_nm, summary.mean_arcmin,
                summary.p2p_arcmin, e.p2p);
    // The twist under the pass's steady torque is near constant: the TE's shape is the
    // excitation's.
    EXPECT_NEAR(summary.p2p_arcmin, e.p2p, 0.25);
  }
}

}  // namespace
}  // namespace wavebench::procedures
