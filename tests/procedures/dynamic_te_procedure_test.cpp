// Dynamic TE on the plant bench: named order peaks and the aliased tooth-mesh line.
#include "wavebench/procedures/dynamic_te_procedure.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "../support/simulated_devices_gear.hpp"
#include "plant_bench.hpp"
#include "wavebench/simdevices/bench_plant.hpp"

namespace wavebench::procedures {
namespace {

const metrology::NamedPeak* peak_near(const metrology::DynamicTeResult& r, double order) {
  for (const auto& p : r.peaks) {
    if (std::abs(p.order_output - order) < 0.1) return &p;
  }
  return nullptr;
}

TEST(DynamicTeProcedure, NamesOutputOnceRevAndMeshAndListsAliasedTeethLines) {
  const auto gear = wavebench::testing::simulated_devices_gear();
  testing::PlantBench bench(gear);
  bench.connect();
  DynamicTeOptions o;  // 100 rpm, two output revolutions: 200 and 202 in separate bins
  o.run_in_s = 1.0;
  int reports = 0;
  const auto out = DynamicTeProcedure(o).run(bench, [&](const std::string&, double) { ++reports; });
  EXPECT_GT(reports, 10);
  const auto& r = out.result;
  EXPECT_GE(r.output_revolutions, 2.0);
  EXPECT_NEAR(r.order_resolution, 0.5, 1e-9);
  EXPECT_NEAR(r.input_speed_hz, 100.0 / 60, 1e-3);
  EXPECT_NEAR(r.sample_rate_hz, 1000, 1e-6);
  EXPECT_EQ(out.teeth.z_flex, 200);

  const auto* once = peak_near(r, 1);
  ASSERT_NE(once, nullptr);
  EXPECT_NE(once->name.find("1/rev"), std::string::npos) << once->name;
  EXPECT_NEAR(once->amplitude_arcsec, 2.4 * 60, 0.1 * 2.4 * 60);
  const auto* mesh = peak_near(r, 200);  // z_F per output revolution
  ASSERT_NE(mesh, nullptr);
  EXPECT_NE(mesh->name, "unnamed");
  const auto* z_circ = peak_near(r, 202);  // the (U, U) tangential error, z_C per output rev
  ASSERT_NE(z_circ, nullptr);
  EXPECT_NE(z_circ->name.find("dF_i1"), std::string::npos) << z_circ->name;
  EXPECT_NEAR(mesh->frequency_hz, 200 * r.input_speed_hz / 100, 1e-2);

  // U·z_C per wave-generator revolution: 404 × 1.667 Hz = 673 Hz, above the 500 Hz Nyquist.
  ASSERT_FALSE(r.aliased.empty());
  bool base_pitch = false;
  for (const auto& a : r.aliased) {
    EXPECT_GT(a.frequency_hz, r.nyquist_hz);
    if (a.name.find("base pitch") != std::string::npos) {
      base_pitch = true;
      EXPECT_NEAR(a.frequency_hz, 404 * 100.0 / 60, 0.5);
      EXPECT_NEAR(a.folded_hz, 1000 - 404 * 100.0 / 60, 0.5);
    }
  }
  EXPECT_TRUE(base_pitch);
  // No peak is reported at a predicted above-Nyquist line's true frequency (it cannot be seen).
  const auto j = out.to_json();
  EXPECT_TRUE(j.contains("peaks"));
  EXPECT_TRUE(j.contains("aliased"));
  EXPECT_TRUE(j["trace"]["te_arcsec"].size() > 100u);
}

TEST(DynamicTeProcedure, PredictsTheToothMeshLineWhenTheTwinHasNone) {
  model::GearParams twin;
  const auto teeth = gear_teeth(twin, 100);
  EXPECT_EQ(teeth.z_flex, 200);
  EXPECT_EQ(teeth.z_circ, 202);
  const auto p = predicted_components(twin, teeth);
  ASSERT_EQ(p.size(), 1u);
  EXPECT_EQ(p[0].order_input, 404);
}

}  // namespace
}  // namespace wavebench::procedures
