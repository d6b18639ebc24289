// The guard-banded verdict (ISO 14253-1) read through the verdict table, the spec's choice of
// how UNDECIDED counts, and repeats combined into one figure with the spread in its budget.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "../support/simulated_devices_gear.hpp"
#include "plant_bench.hpp"
#include "repeat_combination.hpp"
#include "verdict_table.hpp"
#include "wavebench/metrology/uncertainty_budget.hpp"
#include "wavebench/procedures/product_spec.hpp"
#include "wavebench/procedures/run_executor.hpp"
#include "wavebench/procedures/run_limits.hpp"
#include "wavebench/procedures/run_request_check.hpp"
#include "wavebench/simdevices/bench_plant.hpp"

namespace wavebench::procedures {
namespace {

using metrology::UncertainFigure;

nlohmann::json figure_json(double value, double standard, bool varies = true) {
  UncertainFigure f{value, {}};
  f.add("noise after window averaging", standard, 'A', varies);
  f.add("output encoder quantisation", 0.001);
  return metrology::to_json(f);
}

// One static pass whose p2p is 5.98 ± U with U = 2·√(0.02² + 0.001²).
nlohmann::json static_results(double p2p, double standard) {
  return {{"static",
           {{{"direction", "forward"},
             {"load_nm", 0.0},
             {"p2p_arcmin", p2p},
             {"uncertainty", {{"p2p_arcmin", figure_json(p2p, standard)}}}}}}};
}

TEST(UncertainVerdict, ALimitInsideTheIntervalIsUndecidedAndCountsAsTheSpecSays) {
  const auto results = static_results(5.98, 0.02);  // U ≈ 0.04: [5.94, 6.02]
  const nlohmann::json limits = {{"static_p2p_arcmin", 6.0}};
  const auto v = check_limits(limits, results);
  ASSERT_TRUE(v.decision.has_value());
  EXPECT_EQ(*v.decision, metrology::LimitDecision::kUndecided);
  ASSERT_TRUE(v.pass.has_value());  // default: undecided is not a pass
  EXPECT_FALSE(*v.pass);
  ASSERT_EQ(v.checks.size(), 1u);
  const auto& c = v.checks[0];
  EXPECT_EQ(c["decision"], "UNDECIDED");
  EXPECT_EQ(c["path"], "static[0].p2p_arcmin");
  EXPECT_NEAR(c["expanded"].get<double>(), 2 * std::hypot(0.02, 0.001), 1e-12);
  EXPECT_EQ(c["what"], "static[0] forward 0 N·m");
  EXPECT_FALSE(c["pass"].get<bool>());

  EXPECT_TRUE(*check_limits(limits, results, UndecidedCounts::kPass).pass);
  EXPECT_FALSE(check_limits(limits, results, UndecidedCounts::kUndecided).pass.has_value());
  EXPECT_TRUE(
      check_limits(limits, results, UndecidedCounts::kUndecided).checks[0]["pass"].is_null());

  // Wholly within, wholly beyond.
  EXPECT_EQ(*check_limits({{"static_p2p_arcmin", 6.03}}, results).decision,
            metrology::LimitDecision::kPass);
  EXPECT_EQ(*check_limits({{"static_p2p_arcmin", 5.93}}, results).decision,
            metrology::LimitDecision::kFail);
}

TEST(UncertainVerdict, FailOutranksUndecidedAndAMinimumIsGuardBandedBelow) {
  nlohmann::json results = static_results(5.98, 0.02);
  results["static"].push_back({{"direction", "reverse"},
                               {"load_nm", 0.0},
                               {"p2p_arcmin", 7.0},
                               {"uncertainty", {{"p2p_arcmin", figure_json(7.0, 0.02)}}}});
  EXPECT_EQ(*check_limits({{"static_p2p_arcmin", 6.0}}, results).decision,
            metrology::LimitDecision::kFail);
  const nlohmann::json fit = {
      {"lost_motion_fit",
       {{"stiffness",
         {{"k1_nm_per_rad", 3.0e4},
          {"uncertainty", {{"k1_nm_per_rad", figure_json(3.0e4, 500)}}}}}}}};
  EXPECT_EQ(*check_limits({{"min_stiffness_nm_per_rad", 2.95e4}}, fit).decision,
            metrology::LimitDecision::kUndecided);
  EXPECT_EQ(*check_limits({{"min_stiffness_nm_per_rad", 2.8e4}}, fit).decision,
            metrology::LimitDecision::kPass);
}

TEST(UncertainVerdict, TheTableReadsAFigureObjectOrAPlainNumberToo) {
  // A procedure that writes its figure as an uncertain figure object (the torsional test's
  // shape) is read the same way; a plain number is a figure with U = 0.
  const auto found = find_figures({{"x", {{"w", figure_json(1.0, 0.1)}, {"n", 2.0}}}}, "x.w");
  ASSERT_EQ(found.size(), 1u);
  EXPECT_TRUE(found[0].uncertainty_stated);
  EXPECT_DOUBLE_EQ(found[0].figure.value, 1.0);
  const auto plain = find_figures({{"x", {{"n", 2.0}}}}, "x.n");
  ASSERT_EQ(plain.size(), 1u);
  EXPECT_FALSE(plain[0].uncertainty_stated);
  EXPECT_EQ(plain[0].figure.expanded(), 0.0);
  EXPECT_TRUE(find_figures({{"x", 1}}, "y[*].z").empty());
  // Every row of the table names a spec key and a limit key once.
  for (const auto& row : verdict_figures()) {
    int n = 0;
    for (const auto& other : verdict_figures()) n += std::string(other.limit) == row.limit;
    EXPECT_EQ(n, 1) << row.limit;
  }
}

TEST(UncertainVerdict, TheTorsionalTestsFiguresAreJudgedAsFigureObjects) {
  // The torsional procedure writes each figure as an uncertain figure object at its key.
  const nlohmann::json results = {{"torsional",
                                   {{"hysteresis_loss_arcmin", figure_json(0.354, 0.009)},
                                    {"lost_motion_arcmin", figure_json(1.081, 0.011)},
                                    {"stiffness", {{"k1_nm_per_rad", figure_json(28400, 280)}}}}}};
  const auto v = check_limits({{"hysteresis_loss_arcmin", 0.36},
                               {"locked_lost_motion_arcmin", 1.2},
                               {"min_locked_stiffness_nm_per_rad", 2.5e4}},
                              results);
  ASSERT_EQ(v.checks.size(), 3u);
  ASSERT_TRUE(v.decision.has_value());
  // 0.354 + 2·0.009 > 0.36 > 0.354 − 2·0.009: the hysteresis limit lies inside U.
  EXPECT_EQ(*v.decision, metrology::LimitDecision::kUndecided);
  for (const auto& c : v.checks) {
    EXPECT_TRUE(c["uncertainty_stated"].get<bool>()) << c.dump();
    if (c["path"] == "torsional.hysteresis_loss_arcmin") {
      EXPECT_EQ(c["decision"], "UNDECIDED");
    } else {
      EXPECT_EQ(c["decision"], "PASS") << c.dump();
    }
  }
}

TEST(UncertainVerdict, TheSpecChoosesHowUndecidedCountsAndRefusesOtherWords) {
  EXPECT_EQ(
      parse_product_spec("model: X\nlimits:\n  static_te_p2p: 6 arcmin\n", "x", "x.yaml").undecided,
      UndecidedCounts::kFail);
  const auto pass = parse_product_spec(
      "model: X\nundecided: pass\nlimits:\n  static_te_p2p: 6 arcmin\n", "x", "x.yaml");
  EXPECT_EQ(pass.undecided, UndecidedCounts::kPass);
  EXPECT_EQ(pass.to_json()["undecided"], "pass");
  try {
    parse_product_spec("model: X\nundecided: maybe\nlimits:\n  static_te_p2p: 6 arcmin\n", "x",
                       "x.yaml");
    FAIL() << "accepted undecided: maybe";
  } catch (const std::invalid_argument& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("undecided"), std::string::npos) << m;
    EXPECT_NE(m.find("maybe"), std::string::npos) << m;
  }
}

TEST(RepeatCombination, TheMeanWithTheSpreadReplacingWhatVariesBetweenRepeats) {
  const std::vector<nlohmann::json> repeats = {static_results(5.0, 0.01), static_results(5.2, 0.01),
                                               static_results(5.1, 0.01)};
  const auto c = combine_repeats(repeats);
  const auto& entry = c["static"][0];
  EXPECT_NEAR(entry["p2p_arcmin"].get<double>(), 5.1, 1e-12);  // the plain figure follows
  const auto f = metrology::uncertain_figure_from_json(entry["uncertainty"]["p2p_arcmin"]);
  EXPECT_NEAR(f.value, 5.1, 1e-12);
  ASSERT_EQ(f.budget.size(), 2u);
  EXPECT_EQ(f.budget[0].source, "output encoder quantisation");  // kept
  EXPECT_EQ(f.budget[1].source, kRepeatSpreadSource);  // the window noise is in the spread
  EXPECT_NEAR(f.budget[1].standard, 0.1 / std::sqrt(3.0), 1e-12);  // s = 0.1, R = 3
  // Repeats that agree by chance do not claim less than their own noise over √R.
  const auto agree = combine_repeats({static_results(5.0, 0.03), static_results(5.0, 0.03)});
  const auto g =
      metrology::uncertain_figure_from_json(agree["static"][0]["uncertainty"]["p2p_arcmin"]);
  EXPECT_NEAR(g.budget[1].standard, 0.03 / std::sqrt(2.0), 1e-12);
}

TEST(RepeatCombination, AStaticRunWithRepeatsKeepsEachRepeatAndReportsTheirMean) {
  namespace fs = std::filesystem;
  const fs::path root =
      fs::temp_directory_path() / ("wavebench-repeats-" + std::to_string(::getpid()));
  fs::remove_all(root);
  {
    storage::RunStore store(root, "test");
    testing::PlantBench bench(wavebench::testing::simulated_devices_gear());
    bench.connect();
    RunRequest r;
    r.procedure = "static";
    r.options = {{"positions", 4},
                 {"loads_nm", {0}},
                 {"window_s", 0.1},
                 {"repeats", 3},
                 {"calibrate_twin", false}};
    r.config_text = "name: plant\n";
    r.twin = false;
    r.report = false;
    const auto out = execute_run(bench, store, r);
    ASSERT_EQ(out.status, storage::RunStatus::kComplete) << out.reason;
    const auto& j = out.results;
    EXPECT_EQ(j["options"]["repeats"], 3);
    ASSERT_EQ(j["repeats"].size(), 3u);
    for (std::size_t pass = 0; pass < 2; ++pass) {
      double mean = 0;
      for (const auto& rep : j["repeats"])
        mean += rep["static"][pass]["mean_arcmin"].get<double>() / 3;
      EXPECT_NEAR(j["static"][pass]["mean_arcmin"].get<double>(), mean, 1e-12);
      const auto& budget = j["static"][pass]["uncertainty"]["mean_arcmin"]["budget"];
      bool spread = false, noise = false;
      for (const auto& c : budget) {
        spread = spread || c["source"] == kRepeatSpreadSource;
        noise = noise || c["source"] == "noise after window averaging";
      }
      EXPECT_TRUE(spread);
      EXPECT_FALSE(noise);
    }
  }
  fs::remove_all(root);
}

TEST(RepeatCombination, RepeatsAreRefusedOutsideOneToAHundredNamingTheKey) {
  const auto& bench_gear = wavebench::testing::simulated_devices_gear();
  testing::PlantBench bench(bench_gear);
  RunRequest r;
  r.procedure = "dynamic";
  r.options = {{"repeats", 0}};
  try {
    check_run_request(r, bench.description(), 0, std::filesystem::temp_directory_path());
    FAIL() << "accepted repeats 0";
  } catch (const std::invalid_argument& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("dynamic.repeats"), std::string::npos) << m;
    EXPECT_NE(m.find("'0'"), std::string::npos) << m;
  }
  // The estimate grows with the repeats.
  r.options = {{"repeats", 1}};
  const double one =
      check_run_request(r, bench.description(), 0, std::filesystem::temp_directory_path())
          .bench_time_s;
  r.options = {{"repeats", 3}};
  const double three =
      check_run_request(r, bench.description(), 0, std::filesystem::temp_directory_path())
          .bench_time_s;
  EXPECT_NEAR(three, 3 * one, 1e-9 * one);
}

}  // namespace
}  // namespace wavebench::procedures
