// Static TE on the plant bench against the truth computed from the unit's own parameters.
#include "wavebench/procedures/static_te_procedure.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "../support/simulated_devices_gear.hpp"
#include "gear_truth.hpp"
#include "plant_bench.hpp"
#include "wavebench/simdevices/bench_plant.hpp"

namespace wavebench::procedures {
namespace {

using testing::PlantBench;

using testing::Stats;
using testing::stats;

TEST(StaticTeProcedure, EveryPassMatchesTheUnitsTruthWithinATenthOfAnArcminute) {
  const auto gear = wavebench::testing::simulated_devices_gear();
  PlantBench bench(gear);
  bench.connect();
  StaticTeOptions o;
  o.positions = 8;
  o.window_s = 0.2;
  o.loads_nm = {0, 60};
  std::vector<std::string> phases;
  const auto out = StaticTeProcedure(o).run(bench, [&](const std::string& phase, double) {
    if (phases.empty() || phases.back() != phase) phases.push_back(phase);
  });
  ASSERT_EQ(out.passes.size(), 4u);
  EXPECT_EQ(phases.size(), 5u);  // four passes and the analysis
  EXPECT_EQ(out.settle_timeouts, 0);
  const double n = bench.description().sense.ratio;
  for (std::size_t i = 0; i < out.passes.size(); ++i) {
    const auto& pass = out.passes[i];
    const auto& summary = out.result.passes[i];
    const int travel = pass.direction == metrology::Direction::kForward ? 1 : -1;
    ASSERT_EQ(pass.points.size(), 8u);
    std::vector<double> truth;
    for (const auto& p : pass.points) {
      truth.push_back(
          testing::true_static_te(gear, p.theta_in_rad, p.theta_out_rad, p.torque_nm, travel) *
          testing::kArcminPerRadTruth);
      // The held torque is the brake's load in the pass's direction.
      EXPECT_NEAR(p.torque_nm, travel * pass.load_nm * 0.95, 0.5 + 0.1 * pass.load_nm);
      (void)n;
    }
    const auto t = stats(truth);
    SCOPED_TRACE(std::string(metrology::direction_name(pass.direction)) + " " +
                 std::to_string(pass.load_nm));
    EXPECT_NEAR(summary.mean_arcmin, t.mean, 0.1);
    EXPECT_NEAR(summary.p2p_arcmin, t.p2p, 0.1);
    EXPECT_NEAR(summary.std_arcmin, t.std, 0.1);
    std::printf("%s %5.1f N·m: mean %+.3f (truth %+.3f) p2p %.3f (%.3f) std %.3f (%.3f)\n",
                metrology::direction_name(pass.direction), pass.load_nm, summary.mean_arcmin,
                t.mean, summary.p2p_arcmin, t.p2p, summary.std_arcmin, t.std);
  }
  const auto j = out.to_json();
  ASSERT_EQ(j["static"].size(), 4u);
  for (const auto& entry : j["static"]) {
    std::vector<std::string> keys;
    for (const auto& [k, v] : entry.items()) keys.push_back(k);
    std::sort(keys.begin(), keys.end());
    EXPECT_EQ(keys, (std::vector<std::string>{"direction", "load_nm", "mean_arcmin", "p2p_arcmin",
                                              "points", "std_arcmin", "uncertainty"}));
  }
}

// The console's live TE-against-output-angle view: one point per settled position, as it is
// measured, with the figures results.json gives that position.
TEST(StaticTeProcedure, ReportsEachSettledPositionAsResultsGiveIt) {
  PlantBench bench(wavebench::testing::simulated_devices_gear());
  bench.connect();
  StaticTeOptions o;
  o.positions = 4;
  o.window_s = 0.1;
  o.loads_nm = {0, 20};
  StaticTeProcedure procedure(o);
  std::vector<SettledPoint> points;
  procedure.set_point_sink([&](const SettledPoint& p) { points.push_back(p); });
  const auto out = procedure.run(bench);
  ASSERT_EQ(points.size(), 4u * 2u * 2u);
  std::size_t k = 0;
  for (const auto& pass : out.result.passes) {
    for (const auto& r : pass.points) {
      const auto& p = points[k++];
      EXPECT_EQ(p.direction, metrology::direction_name(pass.direction));
      EXPECT_EQ(p.load_nm, pass.load_nm);
      EXPECT_DOUBLE_EQ(p.output_angle_deg, r.output_angle_deg);
      EXPECT_DOUBLE_EQ(p.te_arcsec, r.te_arcmin * 60.0);
      EXPECT_GE(p.output_angle_deg, 0.0);
      EXPECT_LT(p.output_angle_deg, 360.0);
    }
  }
  const nlohmann::json j = points.front();
  for (const char* key : {"output_angle_deg", "te_arcsec", "load_nm", "torque_nm", "direction"}) {
    EXPECT_TRUE(j.contains(key)) << key;
  }
}

TEST(StaticTeOptions, RefuseBadValuesNamingKeyValueAndExpectation) {
  try {
    StaticTeOptions::from_json({{"positions", 1}});
    FAIL();
  } catch (const std::invalid_argument& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("static.positions"), std::string::npos) << m;
    EXPECT_NE(m.find("'1'"), std::string::npos) << m;
    EXPECT_NE(m.find("integer from 2"), std::string::npos) << m;
  }
  EXPECT_THROW(StaticTeOptions::from_json({{"loads_nm", {0, -5}}}), std::invalid_argument);
  EXPECT_THROW(StaticTeOptions::from_json({{"postions", 4}}), std::invalid_argument);
  const auto o = StaticTeOptions::from_json({{"positions", 4}, {"loads_nm", {0, 30}}});
  EXPECT_EQ(o.positions, 4);
  EXPECT_EQ(o.loads_nm, (std::vector<double>{0, 30}));
  EXPECT_EQ(o.window_s, 0.5);
}

}  // namespace
}  // namespace wavebench::procedures
