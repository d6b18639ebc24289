// What a run sends to the shared store, from its index row and results.json.
#include "wavebench/fleet/run_summary.hpp"

#include <gtest/gtest.h>

#include "synthetic_runs.hpp"
#include "wavebench/fleet/fleet_figures.hpp"

namespace wavebench::fleet {
namespace {

storage::RunRecord record(const std::string& procedure) {
  storage::RunRecord r;
  r.id = "20261124T101500.000001Z";
  r.started_at = "2026-11-24T10:15:00.000001Z";
  r.finished_at = "2026-11-24T10:20:00.000001Z";
  r.unit_serial = "U-7";
  r.procedure = procedure;
  r.status = storage::RunStatus::kComplete;
  r.pass = true;
  r.verdict = "PASS";
  r.limits_json = R"({"static_p2p_arcmin": 1.0})";
  r.spec = "csf-25-100";
  r.software_version = "0.1.0";
  r.config_hash = "abc";
  return r;
}

TEST(RunSummary, StaticRunGivesItsTableAndFiguresWithoutPoints) {
  testing::SyntheticRun synthetic;
  synthetic.p2p_forward_arcmin = 0.9;
  synthetic.lost_motion_arcmin = -0.45;  // written negative before issue #11: read by its size
  const auto run = record("static");
  const auto s =
      summarise_run(run, testing::synthetic_results(run.id, synthetic), {"bench-7", "line-2"});
  EXPECT_EQ(s.bench, "bench-7");
  EXPECT_EQ(s.station, "line-2");
  EXPECT_EQ(s.operator_name, "ana");
  EXPECT_EQ(s.gear_model, "CSF-25-100-2A-GR");
  EXPECT_EQ(s.spec, "csf-25-100");
  EXPECT_EQ(s.spec_version.size(), 16u);
  EXPECT_EQ(s.samples_ref, "bench-7:20261124T101500.000001Z/samples.wbs");
  ASSERT_EQ(s.static_passes.size(), 3u);
  EXPECT_EQ(s.static_passes[2].direction, "forward");
  EXPECT_DOUBLE_EQ(s.static_passes[2].load_nm, 60);
  EXPECT_DOUBLE_EQ(*s.static_passes[2].p2p_arcmin, 0.95);
  EXPECT_DOUBLE_EQ(s.figures.at("static_te_p2p"), 0.95);
  EXPECT_DOUBLE_EQ(s.figures.at("static_lost_motion"), 0.45);
  EXPECT_EQ(s.figures.count("k1"), 0u);
  EXPECT_DOUBLE_EQ(s.limits["static_p2p_arcmin"].get<double>(), 1.0);
  EXPECT_FALSE(s.results["static"][0].contains("points"));
  EXPECT_TRUE(s.results["static"][0].contains("p2p_arcmin"));
}

TEST(RunSummary, TorsionalUncertainFiguresAndTwinResiduals) {
  const auto run = record("torsional");
  const nlohmann::json results = {
      {"bench", "sim"},
      {"torsional",
       {{"lost_motion_arcmin", {{"value", 0.8}, {"expanded", 0.05}}},
        {"stiffness",
         {{"k1_nm_per_rad", {{"value", 3.2e4}}},
          {"k2_nm_per_rad", {{"value", 4.1e4}}},
          {"k3_nm_per_rad", {{"value", 5.0e4}}}}},
        {"points", nlohmann::json::array({1, 2})},
        {"mean_curve", {{"torque_nm", {1}}}}}},
      {"twin", {{"calibration", {{"rms_before_arcsec", 9.5}, {"rms_after_arcsec", 1.2}}}}}};
  const auto s = summarise_run(run, results, {});
  EXPECT_EQ(s.bench, "sim");  // results.json's when the config names none
  EXPECT_DOUBLE_EQ(s.figures.at("lost_motion"), 0.8);
  EXPECT_DOUBLE_EQ(s.figures.at("k1"), 3.2e4);
  EXPECT_DOUBLE_EQ(s.figures.at("k3"), 5.0e4);
  EXPECT_DOUBLE_EQ(s.figures.at("twin_residual_before"), 9.5);
  EXPECT_DOUBLE_EQ(s.figures.at("twin_residual_after"), 1.2);
  EXPECT_EQ(s.gear_model, "");
  EXPECT_FALSE(s.results["torsional"].contains("points"));
  EXPECT_FALSE(s.results["torsional"].contains("mean_curve"));
}

// Issue #23 acceptance: the torsional hysteresis loss is trended in the fleet view against its
// spec limit (its declaration names the trend; the columns, the selector and the SPC follow).
TEST(RunSummary, TorsionalHysteresisLossIsTrendedAgainstItsSpecLimit) {
  const auto run = record("torsional");
  const nlohmann::json results = {
      {"torsional",
       {{"hysteresis_loss_arcmin", {{"value", 0.354}, {"expanded", 0.009}}},
        {"lost_motion_arcmin", {{"value", 0.8}, {"expanded", 0.05}}}}}};
  const auto s = summarise_run(run, results, {});
  EXPECT_DOUBLE_EQ(s.figures.at("hysteresis_loss"), 0.354);
  const auto& trend = find_fleet_figure("hysteresis_loss");
  EXPECT_STREQ(trend.column, "hysteresis_loss_arcmin");
  EXPECT_STREQ(trend.unit, "arcmin");
  EXPECT_STREQ(trend.limit_key, "hysteresis_loss_arcmin");  // the spec limit an SPC takes
  EXPECT_FALSE(trend.limit_is_minimum);
  // A static run has none.
  testing::SyntheticRun synthetic;
  const auto other = record("static");
  EXPECT_FALSE(summarise_run(other, testing::synthetic_results(other.id, synthetic), {})
                   .figures.contains("hysteresis_loss"));
}

TEST(RunSummary, RunWithoutResultsSendsItsRowAlone) {
  auto run = record("dynamic");
  run.status = storage::RunStatus::kIncomplete;
  run.reason = "the process ended while the run was running";
  run.pass.reset();
  run.verdict.clear();
  const auto s = summarise_run(run, nullptr, {"bench-7", ""});
  EXPECT_EQ(s.status, "incomplete");
  EXPECT_EQ(s.reason, run.reason);
  EXPECT_TRUE(s.figures.empty());
  EXPECT_EQ(s.verdict, "");
  EXPECT_TRUE(s.results.is_object());
}

}  // namespace
}  // namespace wavebench::fleet
