// The torsional section of a run report from a synthetic run folder: its figures as value ± U,
// the budget behind them, the loop plot (torque on x, twist on y), and its row in the summary
// tables `wavebench run` prints.
#include <gtest/gtest.h>

#include <fstream>
#include <numbers>
#include <sstream>

#include "wavebench/metrology/torsional_loop.hpp"
#include "wavebench/report/run_report.hpp"
#include "wavebench/report/torsional_section.hpp"
#include "wavebench/storage/run_store.hpp"

namespace wavebench::report {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
constexpr double kArcmin = std::numbers::pi / 180 / 60;

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// A torsional section as the procedure writes it, from the loop of a three-segment gear with
// 0.35 arcmin of backlash (the analysis' own JSON, points added as the procedure adds them).
json torsional_results() {
  metrology::ThreeSegmentStiffness law;
  law.k1 = 2.88e4;
  law.t1 = 14;
  law.k2 = 4.32e4;
  law.t2 = 48;
  law.k3 = 5.76e4;
  const double b = 0.35 * kArcmin;
  std::vector<metrology::LoopPoint> loop;
  json points = json::array();
  const auto add = [&](metrology::LoopBranch branch, double t, bool voided = false) {
    const double twist = law.twist_at(t) + (t >= 0 ? b / 2 : -b / 2);
    loop.push_back({branch, t, twist, 1e-8, 1e-3, voided});
    points.push_back({{"branch", metrology::loop_branch_name(branch)},
                      {"torque_nm", t},
                      {"twist_arcmin", twist / kArcmin},
                      {"output_moved_arcmin", voided ? 2.0 : 0.0},
                      {"voided", voided}});
  };
  for (double t = 0.7; t <= 82; t += 0.7) add(metrology::LoopBranch::kFirstLoading, t);
  add(metrology::LoopBranch::kUnloading, 60, true);
  for (double t = 82; t >= -82; t -= 0.7) add(metrology::LoopBranch::kUnloading, t);
  for (double t = -82; t < 0; t += 0.7) add(metrology::LoopBranch::kReloading, t);
  metrology::LoopSensors sensors;
  sensors.ratio = 100;
  sensors.output_encoder_step_rad = 2 * std::numbers::pi / 1048576;
  metrology::TorsionalLoopOptions options;
  options.rated_torque_nm = 100;
  json t = metrology::to_json(metrology::analyse_torsional_loop(loop, sensors, options));
  t["points"] = points;
  t["t_max_nm"] = 82;
  t["t_max_reason"] = "the rated torque 100 N·m, reduced to 82 N·m";
  t["hold_torque_nm"] = 90.25;
  t["rated_torque_nm"] = 100;
  t["slip"] = {{"threshold_arcmin", 1.0}, {"slipped_points", 1}, {"max_output_moved_arcmin", 2.0}};
  return {{"gear", {{"ratio", 100}, {"direction_sign", 1}}}, {"torsional", t}};
}

TEST(TorsionalReport, FiguresWithTheirUncertaintyTheBudgetAndTheLoop) {
  const fs::path root = fs::path(WAVEBENCH_BINARY_DIR) / "test-output" / "torsional-report";
  fs::remove_all(root);
  storage::RunStore store(root / "runs", "wavebench 9.9.9-test");
  const auto id = store.create_run("torsional", "SN-T", "bench: sim\n");
  const auto dir = store.paths(id).dir;
  store.write_results(id, torsional_results());
  store.finish_run(id, storage::RunStatus::kComplete, "", std::nullopt);

  const auto rep = write_run_report(dir);
  const std::string html = slurp(rep.html);
  EXPECT_NE(html.find("Torsional stiffness (locked output)"), std::string::npos);
  // Hysteresis loss 0.350 arcmin, with its U.
  EXPECT_NE(html.find(">0.350 \u00b1 "), std::string::npos);
  EXPECT_NE(html.find("output encoder quantisation"), std::string::npos);
  EXPECT_NE(html.find("expanded (k = 2)"), std::string::npos);
  EXPECT_NE(html.find("reduced to 82"), std::string::npos);
  EXPECT_NE(html.find("<img src=\"torsional.png\""), std::string::npos);
  const std::string png = slurp(dir / "torsional.png");
  EXPECT_EQ(png.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));

  // The figure draws torque on x and twist on y, the voided point apart.
  const auto fig = torsional_loop_figure(torsional_results()["torsional"]);
  ASSERT_TRUE(fig);
  const auto& ax = fig->axes(0, 0);
  EXPECT_NE(ax.x_label.find("torque"), std::string::npos);
  EXPECT_NE(ax.y_label.find("twist"), std::string::npos);
  bool voided = false;
  for (const auto& s : ax.series) voided = voided || s.label.find("voided") != std::string::npos;
  EXPECT_TRUE(voided);

  // The summary tables (`wavebench run` prints them) have the torsional row.
  const auto tables = tables_as_text(session_tables({SessionRun{dir, {}}}));
  EXPECT_NE(tables.find("Torsional stiffness, locked output"), std::string::npos) << tables;
  EXPECT_NE(tables.find("0.350 \u00b1"), std::string::npos) << tables;
  fs::remove_all(root);
}

}  // namespace
}  // namespace wavebench::report
