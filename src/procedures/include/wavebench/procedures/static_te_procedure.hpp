#pragma once
// Static TE (bench.md §4): n positions equally spaced over one output revolution; at each one
// the input moves there (profile position), the output is left to settle (target reached, then
// output speed and drift under thresholds, or the maximum settle time), and θ_in, θ_out and
// torque are averaged over a window. A forward pass, then a reverse pass that approaches each
// position from the other side; both at every load (brake torque).

#include <nlohmann/json.hpp>
#include <string_view>
#include <vector>

#include "wavebench/bench/bench.hpp"
#include "wavebench/metrology/settle_detector.hpp"
#include "wavebench/metrology/static_te_statistics.hpp"
#include "wavebench/procedures/finished_figures.hpp"
#include "wavebench/procedures/option_reader.hpp"
#include "wavebench/procedures/procedure_progress.hpp"
#include "wavebench/procedures/run_plan.hpp"
#include "wavebench/procedures/settled_point.hpp"

namespace wavebench::procedures {

struct StaticTeOptions {
  int positions = 24;
  std::vector<double> loads_nm{0, 60};
  double window_s = 0.5;           // averaging window at each settled position
  double move_speed_rad_s = 62.8;  // input profile velocity (600 rpm)
  double run_up_steps = 0.5;       // run-up before a pass, in position steps
  // The last part of every move is slow: at profile speed the servo overshoots the target and
  // pushes the output across the backlash, leaving it anywhere in the dead zone.
  double approach_rad = 0.5;          // input angle of the slow final approach
  double approach_speed_rad_s = 1.0;  // input
  double brake_settle_s = 0.5;        // after a new brake torque, before the run-up move
  double settle_block_s = 0.02;       // the settle detector sees block means (encoder noise)
  metrology::SettleCriteria settle{5e-4, 1e-5, 0.1, 5.0};

  // From the request's options ({"positions": 24, "loads_nm": [0, 60], ...}); missing keys keep
  // the defaults. Throws std::invalid_argument naming the key, the value and what was expected.
  static StaticTeOptions from_json(const nlohmann::json& options);
  // The options as the console shows them: one entry per key from_json accepts, in order.
  static std::vector<OptionSpec> schema();
  nlohmann::json to_json() const;
};

struct StaticTeOutcome {
  std::vector<metrology::StaticTePass> passes;  // in acquisition order
  metrology::StaticTeResult result;
  int settle_timeouts = 0;  // positions averaged after the maximum settle time ran out
  // results.json: the `static` list (direction, load_nm, mean_arcmin, p2p_arcmin, std_arcmin,
  // points), lost_motion, load_shift, settle_timeouts.
  nlohmann::json to_json() const;
};

class StaticTeProcedure {
 public:
  // Where run()'s outcome goes in results.json: "" for the top level (the static list,
  // lost_motion, load_shift, settle_timeouts stand there since format 1).
  static constexpr std::string_view kResultsSection = "";
  explicit StaticTeProcedure(StaticTeOptions options);
  // What run() will command on `bench` and for how long, without touching it. Throws
  // std::invalid_argument where run() would refuse the options on this bench.
  RunPlan plan(const bench::BenchDescription& bench) const;
  // Throws bench::BenchAborted when the bench trips.
  StaticTeOutcome run(bench::Bench& bench, const ProcedureProgress& progress = {}) const;
  // Where run() reports each settled position as it is measured (none: not reported).
  void set_point_sink(SettledPointSink sink) { point_sink_ = std::move(sink); }
  // Where run() hands over its finished passes after each one (none: not handed over).
  void set_finished_sink(FinishedFiguresSink sink) { finished_sink_ = std::move(sink); }

 private:
  StaticTeOptions options_;
  SettledPointSink point_sink_;
  FinishedFiguresSink finished_sink_;
};

}  // namespace wavebench::procedures
